#!/usr/bin/python3
"""Measurements for filters/asvgf/README.md, of why asvgf does not beat svgf on our scenes: A-SVGF's lambda
against the true change, where each filter's error lies, and where the image's brightness goes, frame by frame
and pass by pass.

    /usr/bin/python3 tools/asvgf_measure.py lambda --dump DUMP --truth TRUTH --frames 6,12,18 [--csv OUT.csv]
    /usr/bin/python3 tools/asvgf_measure.py errors --ref REF --truth TRUTH --frames 6,12,18 \\
        --filtered svgf=DIR --filtered asvgf=DUMP [--csv OUT.csv]
    /usr/bin/python3 tools/asvgf_measure.py brightness --ref REF --dump DUMP --frames 50-60 [--csv OUT.csv]
    /usr/bin/python3 tools/asvgf_measure.py noise --ref REF --frames 0-23 --pair svgf=DIR_SEED0,DIR_SEED1 ...
    /usr/bin/python3 tools/asvgf_measure.py table --metrics EVAL_OUT/metrics.csv [--base svgf]

DUMP is `rtdr filter --method asvgf --dump-passes` output (frame_NNNN.exr with the filter.* layers), TRUTH the same
frames rendered with `rtdr render --true-change --spp N` (trace/true_change.h), REF reference frames (N spp),
EVAL_OUT an `rtdr eval --out` folder. Every folder but EVAL_OUT holds frame_NNNN.exr. The true lambda of a stratum
is Eq. 14 with every pixel of the stratum re-shaded at N spp: |sum (l_i - l_{i-1})| / sum max(l_i, l_{i-1}) over
its covered pixels, l the luminance of the demodulated stream (direct, indirect, or their sum for the `combined`
stream). Nothing here is a filter: it reads what rtdr wrote.
"""
import argparse
import csv
import os
import sys

import numpy as np
import OpenImageIO as oiio

LUMINANCE = np.array([0.2126, 0.7152, 0.0722], dtype=np.float64)  # core/color_shared.h
BINS = [(0.0, 0.02), (0.02, 0.1), (0.1, 0.3), (0.3, 1.01)]  # classes of the true lambda


def read_exr(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit("asvgf_measure: cannot read %s: %s" % (path, oiio.geterror()))
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return {name: pixels[:, :, c].astype(np.float64) for c, name in enumerate(spec.channelnames)}


def frame(folder, f):
    return read_exr(os.path.join(folder, "frame_%04d.exr" % f))


def rgb(layers, name):
    return np.stack([layers[name + "." + c] for c in "RGB"], axis=-1)


def lum(layers, name):
    return rgb(layers, name) @ LUMINANCE


def frames_arg(text):
    if "-" in text and "," not in text:
        a, b = text.split("-")
        return list(range(int(a), int(b) + 1))
    return [int(t) for t in text.split(",")]


def stream_names(dump):
    return ["combined"] if "filter.combined.temporal.R" in dump else ["direct", "indirect"]


def stream_luminance(layers, stream, prefix=""):
    if stream == "combined":
        return lum(layers, prefix + "direct") + lum(layers, prefix + "indirect")
    return lum(layers, prefix + stream)


def per_stratum(plane, covered, s, reduce):
    """reduce() over the covered pixels of each s x s stratum (partial at the borders)."""
    h, w = plane.shape
    out = np.zeros(((h + s - 1) // s, (w + s - 1) // s))
    for sy in range(out.shape[0]):
        for sx in range(out.shape[1]):
            block, cov = plane[sy * s:(sy + 1) * s, sx * s:(sx + 1) * s], covered[sy * s:(sy + 1) * s, sx * s:(sx + 1) * s]
            out[sy, sx] = reduce(block[cov]) if cov.any() else np.nan
    return out


def true_lambda(truth, stream, covered, s):
    now, before = stream_luminance(truth, stream), stream_luminance(truth, stream, "truth.prev_")
    change = per_stratum(now - before, covered, s, np.sum)
    norm = per_stratum(np.maximum(now, before), covered, s, np.sum)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(norm > 0, np.minimum(1.0, np.abs(change) / norm), 0.0)


def cmd_lambda(a):
    rows = []
    for f in frames_arg(a.frames):
        dump, truth = frame(a.dump, f), frame(a.truth, f)
        covered = truth["depth.Z"] > 0
        for stream in stream_names(dump):
            s = a.stratum_size
            lam = dump["filter.%s.lambda" % stream][::s, ::s]
            true = true_lambda(truth, stream, covered, s)
            valid = ~np.isnan(true)
            for lo, hi in BINS:
                sel = valid & (true >= lo) & (true < hi)
                rows.append({"frame": f, "stream": stream, "true_lo": lo, "true_hi": min(hi, 1.0),
                             "strata": int(sel.sum()), "share": sel.sum() / max(1, valid.sum()),
                             "true_mean": float(true[sel].mean()) if sel.any() else float("nan"),
                             "lambda_mean": float(lam[sel].mean()) if sel.any() else float("nan"),
                             "lambda_over_0.25": float((lam[sel] > 0.25).mean()) if sel.any() else float("nan")})
    report(rows, a.csv, ["stream", "true_lo", "true_hi"], ["strata", "share", "true_mean", "lambda_mean",
                                                             "lambda_over_0.25"])


def cmd_errors(a):
    rows = []
    named = [t.split("=", 1) for t in a.filtered]
    for f in frames_arg(a.frames):
        ref, truth = frame(a.ref, f), frame(a.truth, f)
        covered = truth["depth.Z"] > 0
        ref_colour = rgb(ref, "emission") + np.maximum(rgb(ref, "albedo"), 0.001) * (rgb(ref, "direct") + rgb(ref, "indirect"))
        true = true_lambda(truth, "combined", covered, a.stratum_size)
        true_px = np.kron(true, np.ones((a.stratum_size, a.stratum_size)))[:covered.shape[0], :covered.shape[1]]
        for name, folder in named:
            out = frame(folder, f)
            se = ((rgb(out, "color") - ref_colour) ** 2).sum(axis=-1)
            total = se.sum()
            for lo, hi in BINS:
                sel = covered & (true_px >= lo) & (true_px < hi)
                rows.append({"frame": f, "method": name, "true_lo": lo, "true_hi": min(hi, 1.0),
                             "pixels": int(sel.sum()), "share_of_se": se[sel].sum() / total,
                             "rmse_in_class": float(np.sqrt(se[sel].mean() / 3)) if sel.any() else float("nan")})
    report(rows, a.csv, ["method", "true_lo", "true_hi"], ["pixels", "share_of_se", "rmse_in_class"])


def cmd_brightness(a):
    rows = []
    for f in frames_arg(a.frames):
        ref, dump = frame(a.ref, f), frame(a.dump, f)
        albedo, emission = np.maximum(rgb(ref, "albedo"), 0.001), rgb(ref, "emission")
        ref_mean = ((emission + albedo * (rgb(ref, "direct") + rgb(ref, "indirect"))) @ LUMINANCE).mean()
        streams = stream_names(dump)
        stages = [("temporal", "filter.%s.temporal")]
        level = 0
        while "filter.%s.level%d.R" % (streams[0], level) in dump:
            stages.append(("level%d" % level, "filter.%%s.level%d" % level))
            level += 1
        for stage, pattern in stages:
            illumination = sum(rgb(dump, pattern % s) for s in streams)
            mean = ((emission + albedo * illumination) @ LUMINANCE).mean()
            rows.append({"frame": f, "stage": stage, "mean_luminance": mean, "reference": ref_mean,
                         "relative_error": mean / ref_mean - 1.0})
    report(rows, a.csv, ["stage"], ["mean_luminance", "reference", "relative_error"])


def cmd_noise(a):
    """Each method's squared error split into its noise and its bias (lag and blur), from two runs on inputs of two
    seeds: with A and B the two outputs, E(A - B)^2 = 2 sigma^2, so sigma^2 = mean((A - B)^2) / 2 and
    bias^2 = (MSE_A + MSE_B) / 2 - sigma^2 (the reference's own noise stays in the bias)."""
    rows = []
    pairs = [t.split("=", 1) for t in a.pair]
    for f in frames_arg(a.frames):
        ref = frame(a.ref, f)
        ref_colour = rgb(ref, "emission") + np.maximum(rgb(ref, "albedo"), 0.001) * (rgb(ref, "direct") + rgb(ref, "indirect"))
        for name, folders in pairs:
            first, second = folders.split(",")
            x, y = rgb(frame(first, f), "color"), rgb(frame(second, f), "color")
            mse = 0.5 * (((x - ref_colour) ** 2).mean() + ((y - ref_colour) ** 2).mean())
            noise = 0.5 * ((x - y) ** 2).mean()
            rows.append({"frame": f, "method": name, "rmse": np.sqrt(mse), "noise_rms": np.sqrt(noise),
                         "bias_rms": np.sqrt(max(0.0, mse - noise)), "noise_share": noise / mse})
    report(rows, a.csv, ["method"], ["rmse", "noise_rms", "bias_rms", "noise_share"])


def cmd_table(a):
    """A results table from `rtdr eval`'s metrics.csv: per method spec the mean RMSE and SSIM over the frames, and the
    RMSE's change against the spec named by --base (the same row's svgf, say)."""
    rows = list(csv.DictReader(open(a.metrics)))
    specs, order = {}, []
    for r in rows:
        if a.frames and int(r["frame"]) not in frames_arg(a.frames):
            continue
        spec = r["method"] + (":" + r["params"] if r["params"] else "")
        if spec not in specs:
            specs[spec] = []
            order.append(spec)
        specs[spec].append(r)
    mean = {spec: {m: np.mean([float(r[m]) for r in specs[spec]]) for m in ("rmse", "ssim", "brightness_error")}
            for spec in order}
    print("| method | RMSE | SSIM | brightness error | RMSE vs %s |" % a.base)
    print("|---|---|---|---|---|")
    for spec in order:
        base = mean[a.base]["rmse"] if a.base in mean else float("nan")
        print("| %s | %.4f | %.4f | %.3f | %+.1f %% |" % (spec, mean[spec]["rmse"], mean[spec]["ssim"],
                                                         mean[spec]["brightness_error"],
                                                         100.0 * (mean[spec]["rmse"] / base - 1.0)))


def report(rows, path, keys, values):
    """Every row to the CSV; the mean over the frames per key printed."""
    if path:
        with open(path, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0].keys()))
            writer.writeheader()
            writer.writerows(rows)
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[k] for k in keys), []).append(r)
    print("| " + " | ".join(keys + values) + " |")
    print("|" + "---|" * (len(keys) + len(values)))
    for key, group in groups.items():
        cells = ["%g" % k if isinstance(k, float) else str(k) for k in key]
        for v in values:
            vals = np.array([g[v] for g in group], dtype=np.float64)
            cells.append("%.4g" % (np.nanmean(vals) if v != "strata" and v != "pixels" else vals.sum()))
        print("| " + " | ".join(cells) + " |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    for name in ("lambda", "errors", "brightness", "noise"):
        c = sub.add_parser(name)
        c.add_argument("--frames", required=True)
        c.add_argument("--csv")
        c.add_argument("--stratum-size", type=int, default=3)
        if name in ("lambda", "brightness"):
            c.add_argument("--dump", required=True)
        if name in ("lambda", "errors"):
            c.add_argument("--truth", required=True)
        if name in ("errors", "brightness", "noise"):
            c.add_argument("--ref", required=True)
        if name == "noise":
            c.add_argument("--pair", action="append", required=True, help="NAME=DIR_SEED0,DIR_SEED1, repeated")
        if name == "errors":
            c.add_argument("--filtered", action="append", required=True, help="NAME=DIR, repeated")
    t = sub.add_parser("table")
    t.add_argument("--metrics", required=True, help="rtdr eval's metrics.csv")
    t.add_argument("--base", default="svgf", help="the spec the RMSE change is against")
    t.add_argument("--frames", help="only these frames (A-B or A,B,...)")
    a = p.parse_args()
    {"lambda": cmd_lambda, "errors": cmd_errors, "brightness": cmd_brightness, "noise": cmd_noise,
     "table": cmd_table}[a.command](a)


if __name__ == "__main__":
    main()
