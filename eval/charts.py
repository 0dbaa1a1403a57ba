#!/usr/bin/python3
"""The three charts of an evaluation, from the metrics.csv that `rtdr eval` writes.

  speed_vs_accuracy.png  mean ms per frame against mean RMSE (linear HDR), one point per method and
                         parameter setting (the shader ports', backend=vulkan, as green triangles), the Pareto
                         front (nothing both faster and more accurate) marked
  error_over_frames.png  RMSE per frame for each method's default setting (in the style of A-SVGF Fig. 4)
  temporal_error.png     temporal error per frame: mean luminance of the difference of consecutive display
                         frames (SVGF Sec. 5.4, in the style of SVGF Fig. 10)

Usage: /usr/bin/python3 eval/charts.py out/eval/metrics.csv out/eval [--title TEXT]
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
    import matplotlib.pyplot as plt
except ImportError as e:  # one line, as below
    sys.exit("charts.py: error: %s (needs Debian's python3-matplotlib: run tools/setup.sh)" % e)


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key, value in r.items():
            if key not in ("method", "params"):
                r[key] = float(value) if value not in ("", None) else math.nan
    return rows


def label(row):
    """method:params, without alpha_moments when it only repeats alpha (the sweeps set both)."""
    params = ":".join(p for p in row["params"].split(":") if p and not p.startswith("alpha_moments="))
    return row["method"] + (":" + params if params else "")


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


def pareto_front(points):
    """The points no other point beats in both time and error, sorted by time."""
    front = []
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if not front or p[1] < front[-1][1]:
            front.append(p)
    return front


def save(fig, path):
    """Writes the figure to a temporary name beside `path`, then renames it: a reader never sees a partial PNG."""
    tmp = "%s.tmp-%d" % (path, os.getpid())
    try:
        fig.savefig(tmp, dpi=110, format="png")
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def speed_vs_accuracy(groups, out, title):
    points = [(mean([r["ms_total"] for r in g]), mean([r["rmse"] for r in g]), name) for name, g in groups.items()]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for ms, err, name in points:
        if "backend=vulkan" in name:  # the shader ports: device time
            ax.scatter(ms, err, color="tab:green", marker="^", zorder=3)
        else:
            ax.scatter(ms, err, color="tab:blue" if name.startswith("svgf") else "tab:orange", zorder=3)
        ax.annotate(name, (ms, err), textcoords="offset points", xytext=(5, 4), fontsize=7)
    front = pareto_front(points)
    ax.plot([p[0] for p in front], [p[1] for p in front], "k--", lw=1, label="Pareto front", zorder=2)
    ax.set_xscale("symlog", linthresh=1.0)
    ax.set_xlabel("mean time per frame [ms] (golden passes: wall time; backend=vulkan: device time)")
    ax.set_ylabel("mean RMSE against the reference (linear HDR)")
    ax.set_title("Speed versus accuracy" + title)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save(fig, os.path.join(out, "speed_vs_accuracy.png"))


def over_frames(groups, key, ylabel, name, out, title):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for method, g in groups.items():
        if ":" in method:  # parameter sweeps only on the speed chart
            continue
        ax.plot([r["frame"] for r in g], [r[key] for r in g], marker=".", label=method)
    ax.set_xlabel("frame")
    ax.set_ylabel(ylabel)
    ax.set_yscale("log")
    ax.set_title(ylabel + title)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save(fig, os.path.join(out, name))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv")
    parser.add_argument("out")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    groups = group(read_rows(args.csv))
    title = " - " + args.title if args.title else ""
    speed_vs_accuracy(groups, args.out, title)
    over_frames(groups, "rmse", "RMSE (linear HDR)", "error_over_frames.png", args.out, title)
    over_frames(groups, "temporal_error", "temporal error (display)", "temporal_error.png", args.out, title)


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # one line for rtdr eval to quote, not a traceback
        sys.exit("charts.py: error: %s: %s" % (type(e).__name__, e))
