#!/usr/bin/python3
"""The charts of an evaluation, from the metrics.csv that `rtdr eval` writes.

  speed_vs_accuracy.png  one panel per metric (--metrics, default rmse, ssim, flip): mean ms per frame against the
                         metric's mean, one labelled point per method and parameter setting, and the metric's own
                         Pareto front (nothing both faster and better in that metric); the metrics disagree
                         (a method can win FLIP and SSIM and lose RMSE), so each has its panel and its front
  error_over_frames.png  each metric per frame, one panel per metric, for the settings of --lines (in the style
                         of A-SVGF Fig. 4)
  temporal_error.png     temporal error per frame: mean luminance of the difference of consecutive display frames
                         (SVGF Sec. 5.4, in the style of SVGF Fig. 10), with the reference's own change (column
                         ref_temporal_error): the scene's real motion, plus what noise the reference has left
  strip.png              with --tile: the last frame of every method as a labelled grid of crops (eval/strip.py)

A method's family is its name before the first ':' (svgf, asvgf, eaw, a-eaw, accum, none, ...). Each family
has one colour and one marker, the same on every chart (FAMILY_STYLES; a family not listed there takes the
next pair of a fixed cycle, in the order the csv first names it), and the legends, right of the plots, list
them. The shader ports (backend=vulkan, at their device time) keep their family's colour and marker, drawn
open (white inside). Labels are placed by eval/chart_layout.py: none overlaps another or a marker, and each
is nearest its own point or joined to it by a leader line. Method names and the title are shown literally
(a '$' is a dollar sign, not TeX).

Usage: /usr/bin/python3 eval/charts.py out/eval/metrics.csv out/eval [--title TEXT] [--metrics rmse,ssim,flip]
           [--lines SPEC,SPEC] [--tile LABEL PNG ... --crop auto|full|X,Y,W,H]
Needs Debian's numpy and matplotlib (python3-numpy, python3-matplotlib), installed by tools/setup.sh.
Each chart is written under a temporary name and renamed, so a failure (a full disk, say) leaves no partial
PNG; it prints one line, "charts.py: error: ...", and exits with status 1.
"""
import argparse
import csv
import math
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")  # no display: write files only
    matplotlib.rcParams["text.usetex"] = False  # user text is never TeX (chart_layout.literal)
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator

    import chart_layout
    import strip
    from chart_layout import literal
except ImportError as e:  # one line, as below
    sys.exit("charts.py: error: %s (needs Debian's python3-matplotlib: run tools/setup.sh)" % e)

DPI = 110  # figures are laid out and saved at one resolution, so the measured label boxes are the saved ones
MARKER_AREA = chart_layout.MARKER_AREA

# family: (colour, marker). Filled markers only, so that an open (port) marker reads as the same shape.
FAMILY_STYLES = {
    "svgf": ("tab:blue", "o"),
    "asvgf": ("tab:purple", "D"),
    "eaw": ("tab:orange", "s"),
    "a-eaw": ("tab:red", "P"),
    "eaw-accum": ("tab:brown", "X"),
    "accum": ("tab:olive", "v"),
    "none": ("tab:gray", "h"),
    "taa": ("tab:pink", "<"),
    "trmv": ("tab:green", "^"),
}
# Families not listed above take colour i % 7 and marker i % 6 of these; 7 and 6 are coprime, so the first
# 42 such families all get a different pair.
OTHER_COLOURS = ["tab:cyan", "#393b79", "#8c6d31", "#843c39", "#7b4173", "#637939", "#17becf"]
OTHER_MARKERS = [">", "p", "d", "8", "H", "*"]

# metric column: (axis label, whether higher is better, logarithmic axis over frames where it spans a decade)
METRICS = {
    "rmse": ("RMSE (linear HDR)", False, True),
    "relmse": ("relMSE (linear HDR)", False, True),
    "ssim": ("SSIM (display)", True, False),
    "flip": ("FLIP (display)", False, True),
    "umbra_rmse": ("RMSE in the moving umbrae", False, True),
    "temporal_error": ("temporal error (display)", False, True),
}


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key, value in r.items():
            if key not in ("method", "params"):
                r[key] = float(value) if value not in ("", None) else math.nan
    return rows


def spec_label(spec):
    """A method spec as the charts name it: without alpha_moments when it only repeats alpha (the sweeps set both)."""
    name, _, params = spec.partition(":")
    params = ":".join(p for p in params.split(":") if p and not p.startswith("alpha_moments="))
    return name + (":" + params if params else "")


def label(row):
    return spec_label(row["method"] + ":" + row["params"])


def family(name):
    """The method family of a label or method name: what comes before the first ':'."""
    return name.split(":", 1)[0].strip()


def is_port(name):
    return "backend=vulkan" in name


def family_styles(families):
    """{family: (colour, marker)} for `families` (in order of first appearance): the listed families keep
    their FAMILY_STYLES entry, every other one takes the next pair of the fixed cycle."""
    styles, others = {}, 0
    for f in families:
        if f in styles:
            continue
        if f in FAMILY_STYLES:
            styles[f] = FAMILY_STYLES[f]
        else:
            styles[f] = (OTHER_COLOURS[others % len(OTHER_COLOURS)], OTHER_MARKERS[others % len(OTHER_MARKERS)])
            others += 1
    return styles


def group(rows):
    """Rows by method label, each list in frame order."""
    groups = {}
    for r in rows:
        groups.setdefault(label(r), []).append(r)
    for g in groups.values():
        g.sort(key=lambda r: r["frame"])
    return groups


def mean(values):
    values = [v for v in values if not math.isnan(v)]
    return sum(values) / len(values) if values else math.nan


def pareto_front(points, higher_is_better=False):
    """The points (ms, value, ...) no other point beats in both time and value, sorted by time."""
    sign = -1.0 if higher_is_better else 1.0
    front = []
    for p in sorted(points, key=lambda p: (p[0], sign * p[1])):
        if not front or sign * p[1] < sign * front[-1][1]:
            front.append(p)
    return front


def save(fig, path):
    """Writes the figure to a temporary name beside `path`, then renames it: a reader never sees a partial PNG."""
    tmp = "%s.tmp-%d" % (path, os.getpid())
    try:
        fig.savefig(tmp, dpi=DPI, format="png")
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def legend_handles(names, styles, front=False):
    """One entry per family among `names`, in the order of `styles`, then the ports' open marker and the front."""
    shown = {family(n) for n in names}
    handles = [Line2D([], [], ls="", marker=m, color=c, label=f) for f, (c, m) in styles.items() if f in shown]
    if any(is_port(n) for n in names):
        handles.append(Line2D([], [], ls="", marker="o", mfc="white", mec="0.3", mew=1.2,
                              label="open: backend=vulkan\n(shader port, device time)"))
    if front:
        handles.append(Line2D([], [], color="k", ls="--", lw=1, label="Pareto front\n(of each panel's metric)"))
    return handles


def speed_vs_accuracy(groups, styles, out, title, metrics=("rmse", "ssim", "flip")):
    """One panel per metric: mean ms against the metric's mean, every setting labelled, the metric's front."""
    metrics = [m for m in metrics if any(m in g[0] for g in groups.values())]
    ms = {name: mean([r["ms_total"] for r in g]) for name, g in groups.items()}
    fig, axes = plt.subplots(len(metrics), 1, figsize=(11, 1.0 + 3.9 * len(metrics)), dpi=DPI, squeeze=False)
    axes = axes[:, 0]
    panels = []
    for ax, metric in zip(axes, metrics):
        name, higher, _ = METRICS.get(metric, (metric, False, True))
        points = [(ms[n], mean([r[metric] for r in g]), n) for n, g in groups.items()]
        points = [p for p in points if math.isfinite(p[0]) and p[0] > 0 and math.isfinite(p[1])]
        for x, y, n in points:
            colour, marker = styles[family(n)]
            face = "white" if is_port(n) else colour  # the shader ports: open markers, at their device time
            ax.scatter(x, y, s=MARKER_AREA, marker=marker, facecolors=face, edgecolors=colour, linewidths=1.2,
                       zorder=3)
        front = pareto_front(points, higher)
        ax.plot([p[0] for p in front], [p[1] for p in front], "k--", lw=1, zorder=2)
        chart_layout.set_ms_axis(ax, [p[0] for p in points])
        ax.margins(y=0.12)
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.set_ylabel("mean %s\n(%s is better)" % (name, "higher" if higher else "lower"))
        ax.grid(True, alpha=0.3)
        panels.append((ax, points, front))
    axes[0].set_title(literal("Speed versus accuracy" + title))
    axes[-1].set_xlabel("mean time per frame [ms] (golden passes: wall time; backend=vulkan: device time)")
    chart_layout.legend_outside(fig, legend_handles(list(groups), styles, front=True), axes[0])
    for ax, points, front in panels:
        chart_layout.place_labels(ax, [p[:2] for p in points], [p[2] for p in points],
                                  colours=[styles[family(p[2])][0] for p in points],
                                  lines=[([p[0] for p in front], [p[1] for p in front])])
    save(fig, os.path.join(out, "speed_vs_accuracy.png"))


def over_frames(groups, styles, metrics, lines, name, out, title, reference=None):
    """Each metric per frame, one panel each, one curve per setting of `lines`; `reference`: a column drawn as
    the reference's own curve (black, dashed)."""
    metrics = [m for m in metrics if any(m in g[0] for g in groups.values())]
    fig, axes = plt.subplots(len(metrics), 1, figsize=(10, 0.8 + 3.2 * len(metrics)), dpi=DPI, squeeze=False,
                             sharex=True)
    axes = axes[:, 0]
    handles = []
    for ax, metric in zip(axes, metrics):
        ylabel, _, log = METRICS.get(metric, (metric, False, True))
        for method in lines:
            colour, marker = styles[family(method)]
            g = groups[method]
            (line,) = ax.plot([r["frame"] for r in g], [r[metric] for r in g], color=colour, marker=marker, ms=4,
                              mfc="white" if is_port(method) else colour, label=method)
            if ax is axes[0]:
                handles.append(line)
        if reference and any(reference in g[0] for g in groups.values()):
            g = next(iter(groups.values()))
            (line,) = ax.plot([r["frame"] for r in g], [r[reference] for r in g], color="k", ls="--", lw=1.5,
                              label="reference: its own change\n(the scene's motion, and\nthe noise it has left)")
            if ax is axes[0]:
                handles.append(line)
        ax.set_ylabel(ylabel)
        values = [v for line in ax.lines for v in line.get_ydata() if math.isfinite(v) and v > 0]
        if log and values and max(values) > 10 * min(values):  # logarithmic only where it spans a decade
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
    axes[0].set_title(literal(("Temporal error" if reference else "Error per frame") + title))
    axes[-1].set_xlabel("frame")
    axes[-1].xaxis.set_major_locator(MaxNLocator(integer=True))
    if handles:  # a csv of sweeps only has no setting to draw
        chart_layout.legend_outside(fig, handles, axes[0])
    else:
        fig.tight_layout()
    save(fig, os.path.join(out, name))


def line_settings(groups, lines):
    """The settings drawn over frames: those of --lines (specs, as rtdr eval passes the ones the user named)
    that ran, or without --lines every setting without parameters."""
    if lines is None:
        return [n for n in groups if ":" not in n]
    wanted = [spec_label(s) for s in lines.split(",") if s]
    return [n for n in wanted if n in groups]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv")
    parser.add_argument("out")
    parser.add_argument("--title", default="")
    parser.add_argument("--metrics", default="rmse,ssim,flip", help="comma-separated metric columns")
    parser.add_argument("--lines", default=None, help="comma-separated method specs drawn over frames")
    parser.add_argument("--tile", nargs=2, action="append", default=[], metavar=("LABEL", "PNG"),
                        help="a tile of strip.png, in order")
    parser.add_argument("--crop", default="auto", help="strip.png's crop: auto, full or X,Y,W,H")
    args = parser.parse_args()
    metrics = [m for m in args.metrics.split(",") if m]
    unknown = [m for m in metrics if m not in METRICS]
    if unknown:
        raise ValueError("--metrics: %s is not one of %s" % (",".join(unknown), ",".join(METRICS)))
    crop = strip.parse_crop(args.crop)  # before any chart is drawn
    groups = group(read_rows(args.csv))
    styles = family_styles(family(name) for name in groups)
    title = " - " + args.title if args.title else ""
    lines = line_settings(groups, args.lines)
    speed_vs_accuracy(groups, styles, args.out, title, metrics)
    over_frames(groups, styles, [m for m in metrics if m != "temporal_error"], lines, "error_over_frames.png",
                args.out, title)
    over_frames(groups, styles, ["temporal_error"], lines, "temporal_error.png", args.out, title,
                reference="ref_temporal_error")
    if args.tile:
        strip.draw_strip(args.tile, crop, os.path.join(args.out, "strip.png"), title, save, DPI)


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # one line for rtdr eval to quote, not a traceback
        sys.exit("charts.py: error: %s: %s" % (type(e).__name__, e))
