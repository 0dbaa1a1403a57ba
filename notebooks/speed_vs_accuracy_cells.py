"""The cells of speed_vs_accuracy.ipynb: the metrics of `rtdr eval`, charts and the trade-off (make_notebooks.py
writes the notebook)."""
from nbformat.v4 import new_code_cell, new_markdown_cell

from common_cell import COMMON

SPEED = [
    new_markdown_cell("""# Speed versus accuracy

Every method, and the SVGF parameter sweeps, on one scene, measured by `rtdr eval` against reference
frames. `RTDR_METRICS` names the `metrics.csv` (default: pillars' in `bash tools/demo.sh --full`). RMSE is on linear
HDR radiance; SSIM and FLIP on tone-mapped display values (eval/experiment.h). Times are the golden CPU
passes on this machine: they rank the methods, they are not GPU times."""),
    new_code_cell(COMMON + '''
import csv, math

METRICS = os.environ.get("RTDR_METRICS", "out/demo/full/pillars/metrics.csv")
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
