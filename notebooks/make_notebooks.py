#!/usr/bin/python3
"""Writes the classroom notebooks from the cells below, without outputs (run with /usr/bin/python3).

  svgf_walkthrough.ipynb   each SVGF pass on a real frame, in the order of filters/svgf/README.md
  speed_vs_accuracy.ipynb  the metrics of `rtdr eval`: charts and the trade-off

Both read their data from environment variables (defaults: what tools/demo.sh and the README's commands
write), so the test suite can run them on a tiny sequence: tests/run_notebooks.sh.
"""
import os

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = os.path.dirname(os.path.abspath(__file__))

COMMON = '''import json, os, subprocess
import numpy as np
import matplotlib.pyplot as plt
import OpenImageIO as oiio

def read_exr(path):
    """All channels of a multi-layer EXR as a dict name -> 2D float array (docs/buffers.md)."""
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError(f"cannot open {path}: {oiio.geterror()}")
    pixels = inp.read_image(format="float")
    names = list(inp.spec().channelnames)
    inp.close()
    return {name: pixels[..., k] for k, name in enumerate(names)}

def rgb(frame, layer):
    return np.stack([frame[f"{layer}.{c}"] for c in "RGB"], axis=-1)

def show(images, titles, cmap=None):
    fig, axes = plt.subplots(1, len(images), figsize=(4 * len(images), 2.6))
    for ax, image, title in zip(np.atleast_1d(axes), images, titles):
        ax.imshow(image, cmap=cmap)
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    plt.show()

def display(c):
    """Linear radiance to a viewable image: Reinhard c / (1 + c), then the sRGB curve."""
    c = np.clip(c / (1.0 + c), 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)'''

WALKTHROUGH = [
    new_markdown_cell("""# SVGF, pass by pass

Spatiotemporal Variance-Guided Filtering (Schied et al. 2017) on a real frame rendered by RTDR. Each
section is one pass, in the order of `filters/svgf/README.md`; every image is a layer that
`rtdr filter --dump-passes` wrote (names in `docs/buffers.md`), and the last section prints the terms of
one pixel with `rtdr probe`.

The data comes from `RTDR_WALKTHROUGH_IN` (the rendered 1-spp frames) and `RTDR_WALKTHROUGH_DUMP` (the
filtered frames with their dumps). To make them yourself:

```sh
build/app/rtdr render --scene pillars --frames 0-9 --size 320x180 --out out/walkthrough/in
build/app/rtdr filter --method svgf --in out/walkthrough/in --out out/walkthrough/svgf --dump-passes
```"""),
    new_code_cell(COMMON + '''

IN = os.environ.get("RTDR_WALKTHROUGH_IN", "out/walkthrough/in")
DUMP = os.environ.get("RTDR_WALKTHROUGH_DUMP", "out/walkthrough/svgf")
RTDR = os.environ.get("RTDR_EXE", "build/app/rtdr")
frames = sorted(f for f in os.listdir(DUMP) if f.endswith(".exr"))
last = frames[-1]
frame_index = int(last[6:10])
inp, out = read_exr(os.path.join(IN, last)), read_exr(os.path.join(DUMP, last))
print(f"{len(frames)} frames; looking at {last}, {inp['depth.Z'].shape[1]}x{inp['depth.Z'].shape[0]}")'''),
    new_markdown_cell("""## 0. The input: demodulated 1-spp illumination [SVGF17 Sec. 3]

The path tracer's radiance divided by the albedo, direct and indirect apart. Texture is gone, so the
filter never blurs it; the noise is what is left."""),
    new_code_cell('''show([display(rgb(inp, "direct")), display(rgb(inp, "indirect")), rgb(inp, "albedo")],
     ["direct (demodulated)", "indirect (demodulated)", "albedo"])'''),
    new_markdown_cell("""## 1. Temporal accumulation [SVGF17 Sec. 4.1]

Each pixel is back-projected with its motion vector; consistent history is blended with
alpha = max(0.2, 1/n). The history length n is 1 after a disocclusion: watch the trailing edges of the
moving pillars."""),
    new_code_cell('''n = out["filter.direct.history_length"]
show([display(out_rgb) for out_rgb in [np.stack([out[f"filter.direct.temporal.{c}"] for c in "RGB"], -1)]] + [n],
     ["integrated colour C'", f"history length n (max {n.max():.0f})"])'''),
    new_markdown_cell("""## 2. Variance [SVGF17 Sec. 4.2]

sigma^2 = mu2' - mu1'^2 from the integrated luminance moments; where n < 4 a 7x7 spatial estimate. Bright
means noisy: the filter will blur more there."""),
    new_code_cell('''var = out["filter.direct.variance"]
show([np.sqrt(var), out["filter.direct.moments.mu1"]], ["standard deviation sqrt(sigma^2)", "mu1' (mean luminance)"], cmap="magma")'''),
    new_markdown_cell("""## 3. The a-trous levels [SVGF17 Eq. 1-5]

Five levels, each 25 taps spaced 2^i apart, weighted by depth (Eq. 3), normals (Eq. 4) and luminance
against the prefiltered variance (Eq. 5). The variance shrinks level by level, so the luminance weight
grows stricter."""),
    new_code_cell('''levels = sorted({k.split(".")[2] for k in out if k.startswith("filter.direct.level") and k.endswith(".R")})
show([display(np.stack([out[f"filter.direct.{l}.{c}"] for c in "RGB"], -1)) for l in levels], levels)
print("mean variance per level:", [float(out[f"filter.direct.{l}.variance"].mean()) for l in levels])'''),
    new_markdown_cell("""## 4. Remodulated, recombined, tone mapped, antialiased [SVGF17 Sec. 3]"""),
    new_code_cell('''noisy = rgb(inp, "emission") + np.maximum(rgb(inp, "albedo"), 1e-3) * (rgb(inp, "direct") + rgb(inp, "indirect"))
show([display(noisy), display(rgb(out, "color")), rgb(out, "display")], ["1-spp input", "SVGF colour", "display (TAA)"])'''),
    new_markdown_cell("""## 5. One pixel, every term: `rtdr probe`

The weights of every tap of a-trous level 1 at a pixel on the floor, as a shader port would compare them."""),
    new_code_cell('''h, w = inp["depth.Z"].shape
x, y = w // 2, int(h * 0.8)
probe = json.loads(subprocess.run([RTDR, "probe", "--in", IN, "--frame", str(frame_index), "--pixel", f"{x},{y}",
                                   "--pass", "atrous", "--level", "1", "--json"], check=True,
                                  capture_output=True, text=True).stdout)
taps = {}
for t in probe["terms"]:
    if t["group"].startswith("tap"):
        taps.setdefault(t["group"], {})[t["name"]] = t["value"]
print(f"pixel ({x}, {y}), {len(taps)} taps")
print(f"{'tap':>14} {'h':>8} {'w_z':>8} {'w_n':>8} {'w_l':>8}")
for name, terms in taps.items():
    if "h(q)" in terms:
        print(f"{name:>14} {terms['h(q)'][0]:8.4f} {terms['w_z'][0] if 'w_z' in terms else 1:8.4f} "
              f"{terms['w_n'][0] if 'w_n' in terms else 1:8.4f} {terms['w_l'][0] if 'w_l' in terms else 1:8.4f}")'''),
]

SPEED = [
    new_markdown_cell("""# Speed versus accuracy

Every method, and the SVGF parameter sweeps, on one scene, measured by `rtdr eval` against reference
frames. `RTDR_METRICS` names the `metrics.csv` (default: what `bash tools/demo.sh` writes). RMSE is on linear
HDR radiance; SSIM and FLIP on tone-mapped display values (eval/experiment.h). Times are the golden CPU
passes on this machine: they rank the methods, they are not GPU times."""),
    new_code_cell(COMMON + '''
import csv, math

METRICS = os.environ.get("RTDR_METRICS", "out/demo/metrics.csv")
with open(METRICS, newline="") as f:
    rows = list(csv.DictReader(f))
def label(r):
    return r["method"] + (":" + r["params"] if r["params"] else "")
methods = {}
for r in rows:
    methods.setdefault(label(r), []).append(r)
def mean(rs, key):
    values = [float(r[key]) for r in rs if r[key] not in ("", "nan")]
    return sum(values) / len(values) if values else math.nan
table = sorted(((name, mean(rs, "ms_total"), mean(rs, "rmse"), mean(rs, "ssim"), mean(rs, "flip")) for name, rs in methods.items()),
               key=lambda t: t[1])
print(f"{'method':45} {'ms':>8} {'RMSE':>8} {'SSIM':>6} {'FLIP':>6}")
for name, ms, e, s, fl in table:
    print(f"{name:45} {ms:8.1f} {e:8.4f} {s:6.3f} {fl:6.3f}")'''),
    new_markdown_cell("""## The Pareto front

A method is on the front when no other is both faster and more accurate. Accumulation alone is cheap but
keeps the noise its short history cannot average away; the a-trous levels buy accuracy at a cost per
level; the colour history's alpha trades lag against noise."""),
    new_code_cell('''front, best = [], math.inf
for name, ms, e, s, fl in table:
    if e < best:
        front.append((ms, e, name)); best = e
fig, ax = plt.subplots(figsize=(7, 4.5))
for name, ms, e, s, fl in table:
    ax.scatter(ms, e, color="tab:blue" if name.startswith("svgf") else "tab:orange")
    ax.annotate(name, (ms, e), fontsize=7, xytext=(4, 3), textcoords="offset points")
ax.plot([p[0] for p in front], [p[1] for p in front], "k--", lw=1, label="Pareto front")
ax.set_xscale("symlog", linthresh=1.0); ax.set_xlabel("ms per frame"); ax.set_ylabel("mean RMSE"); ax.legend()
plt.show()
print("on the front:", ", ".join(p[2] for p in front))'''),
    new_markdown_cell("""## Error over frames

Temporal methods start where the input is and improve as history builds; where shadows move (pillars,
fence) their error grows again as stale history lags behind the geometry: the failure A-SVGF addresses."""),
    new_code_cell('''fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
for name, rs in methods.items():
    if ":" in name:
        continue
    frames = [int(r["frame"]) for r in rs]
    axes[0].plot(frames, [float(r["rmse"]) for r in rs], marker=".", label=name)
    axes[1].plot(frames, [float(r["temporal_error"]) for r in rs], marker=".", label=name)
axes[0].set_title("RMSE"); axes[1].set_title("temporal error (display)")
for ax in axes:
    ax.set_yscale("log"); ax.set_xlabel("frame"); ax.legend(fontsize=7)
plt.show()'''),
]


def write(name, cells):
    for i, cell in enumerate(cells):  # fixed ids, so regenerating gives the same bytes
        cell["id"] = f"{name.split('.')[0]}-{i:02d}"
    nb = new_notebook(cells=cells, metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                                               "language": "python"}})
    path = os.path.join(HERE, name)
    with open(path, "w") as f:
        nbformat.write(nb, f)
    print("wrote", path)


if __name__ == "__main__":
    write("svgf_walkthrough.ipynb", WALKTHROUGH)
    write("speed_vs_accuracy.ipynb", SPEED)
