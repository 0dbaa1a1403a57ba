#!/usr/bin/python3
"""The labels of eval/charts.py's speed chart stay readable where points cluster (ctest: `eval_charts`).

Usage: eval_charts_test.py [SOURCE_DIR]   (default: the folder above this script's)

It writes a metrics.csv of 21 settings in the columns `rtdr eval` writes, clustered as the SVGF sweeps and the
pillars scene cluster them (seven points lie within 1% of svgf's default in both time and error, the two
ports' points within 1% of each other), draws the speed chart with charts.py's own speed_vs_accuracy, and
checks on the figure as saved, in display coordinates with the renderer's text extents:

  1. every point has its label, and no two label boxes intersect;
  2. every label box lies inside the figure, and inside the axes;
  3. no label box covers a marker;
  4. the same csv gives the same placement (place_labels is deterministic);
  5. the csv is hard enough: labels at the old fixed offset (5, 4) points would overlap (else 1 to 3 prove
     nothing);
  6. the known families have distinct colours and distinct markers, and families charts.py does not know get
     pairs that differ from those and from each other, in order of first appearance;
  7. the command line writes the three PNGs and no temporary file, and a missing csv gives one line,
     "charts.py: error: ...", and status 1.

Prints one line per failed check and exits 1 when there is any.
"""
import csv
import itertools
import math
import os
import subprocess
import sys
import tempfile

SOURCE_DIR = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(SOURCE_DIR, "eval"))
import charts  # noqa: E402  (eval/charts.py, found through the path above)

# (method, params, mean ms per frame, mean RMSE): the svgf sweeps around the default at (12.0, 0.0500).
SETTINGS = [
    ("svgf", "", 12.0, 0.0500),
    ("svgf", "atrous_levels=1", 8.0, 0.080), ("svgf", "atrous_levels=2", 9.0, 0.062),
    ("svgf", "atrous_levels=3", 10.0, 0.055), ("svgf", "atrous_levels=4", 11.0, 0.051),
    ("svgf", "atrous_levels=5", 12.05, 0.0502),
    ("svgf", "alpha=0.05:alpha_moments=0.05", 12.02, 0.0498), ("svgf", "alpha=0.1:alpha_moments=0.1", 12.01, 0.0501),
    ("svgf", "alpha=0.2:alpha_moments=0.2", 11.98, 0.0504), ("svgf", "alpha=0.5:alpha_moments=0.5", 12.03, 0.0560),
    ("svgf", "kernel=3", 11.9, 0.0503),
    ("svgf", "backend=vulkan:illumination=fp32", 1.20, 0.0500),
    ("svgf", "backend=vulkan:illumination=fp16", 1.21, 0.0501),
    ("asvgf", "", 14.0, 0.0450), ("asvgf", "backend=vulkan", 1.5, 0.0452),
    ("eaw", "", 6.0, 0.070), ("a-eaw", "", 6.05, 0.0702), ("eaw-accum", "", 6.5, 0.065),
    ("accum", "", 0.5, 0.120), ("none", "", 0.01, 0.200), ("nrd-relax", "", 3.0, 0.060),
]
FRAMES = 3
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def write_csv(path):
    """The columns `rtdr eval` writes; frame f of a setting is off its mean by (f - 1) percent."""
    columns = ["method", "params", "frame", "rmse", "relmse", "ssim", "flip", "temporal_error",
               "brightness_error", "ms_total", "ms_atrous"]
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(columns)
        for method, params, ms, rmse in SETTINGS:
            for frame in range(FRAMES):
                k = 1 + (frame - 1) / 100
                temporal = "nan" if frame == 0 else 0.005 * k
                out.writerow([method, params, frame, rmse * k, 2 * rmse, 0.8, 0.2, temporal, 0.1, ms * k, ms / 2])


def draw_speed_chart(csv_path, out):
    """charts.speed_vs_accuracy on `csv_path`; returns, measured as the figure is saved, the label boxes, the
    marker boxes, the figure's and the axes' boxes and the boxes that labels at the old offset would take."""
    groups = charts.group(charts.read_rows(csv_path))
    styles = charts.family_styles(charts.family(name) for name in groups)
    seen = {}

    def measuring_save(fig, path):
        ax = fig.axes[0]
        renderer = fig.canvas.get_renderer()
        labels = [tuple(t.get_window_extent(renderer).extents) for t in ax.texts]
        xy = ax.transData.transform([o for c in ax.collections for o in c.get_offsets()])
        r = math.sqrt(charts.MARKER_AREA) / 2 * fig.dpi / 72
        seen["markers"] = [(x - r, y - r, x + r, y + r) for x, y in xy]
        old_offset = (5 * fig.dpi / 72, 4 * fig.dpi / 72)
        seen["old"] = [(x + old_offset[0], y + old_offset[1], x + old_offset[0] + (b[2] - b[0]),
                        y + old_offset[1] + (b[3] - b[1])) for (x, y), b in zip(xy, labels)]
        seen.update(labels=labels, texts=[t.get_text() for t in ax.texts], figure=fig.bbox.extents,
                    axes=ax.bbox.extents)
        real_save(fig, path)

    real_save, charts.save = charts.save, measuring_save
    try:
        charts.speed_vs_accuracy(groups, styles, out, " - clustered")
    finally:
        charts.save = real_save
    return seen


def intersect(a, b):
    return min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1])


def within(a, outer):
    return a[0] >= outer[0] and a[1] >= outer[1] and a[2] <= outer[2] and a[3] <= outer[3]


def test_placement(csv_path, out):
    seen = draw_speed_chart(csv_path, out)
    labels, texts = seen["labels"], seen["texts"]
    check(sorted(texts) == sorted(charts.label({"method": m, "params": p}) for m, p, _, _ in SETTINGS),
          "the labels are not one per setting: %s" % texts)
    for (a, ta), (b, tb) in itertools.combinations(zip(labels, texts), 2):
        check(not intersect(a, b), "labels %r and %r overlap" % (ta, tb))
    for box, text in zip(labels, texts):
        check(within(box, seen["figure"]), "label %r leaves the figure" % text)
        check(within(box, seen["axes"]), "label %r leaves the axes" % text)
        check(not any(intersect(box, m) for m in seen["markers"]), "label %r covers a marker" % text)
    check(any(intersect(a, b) for a, b in itertools.combinations(seen["old"], 2)),
          "the points are not clustered enough: labels at the old fixed offset would not overlap")
    again = draw_speed_chart(csv_path, out)
    check(again["labels"] == labels, "a second drawing of the same csv placed the labels elsewhere")


def test_styles():
    known = list(charts.FAMILY_STYLES)
    for name in ["svgf", "asvgf", "eaw", "a-eaw", "accum", "none"]:
        check(name in known, "family %s has no style of its own" % name)
    styles = charts.family_styles(["zeta", "svgf", "alpha", "zeta", "beta"] + known)
    colours = [styles[f][0] for f in known]
    markers = [styles[f][1] for f in known]
    check(len(set(colours)) == len(colours), "two known families share a colour: %s" % colours)
    check(len(set(markers)) == len(markers), "two known families share a marker: %s" % markers)
    check(all(styles[f] == charts.FAMILY_STYLES[f] for f in known), "a known family's style depends on the csv")
    new = [styles[f] for f in ["zeta", "alpha", "beta"]]
    check(len(set(new)) == 3 and not set(c for c, _ in new) & set(colours)
          and not set(m for _, m in new) & set(markers), "the unknown families' styles are not distinct: %s" % new)
    check(new == [(charts.OTHER_COLOURS[i], charts.OTHER_MARKERS[i]) for i in range(3)],
          "the unknown families do not take the cycle in order of first appearance: %s" % new)
    check(charts.family("svgf:backend=vulkan:illumination=fp16") == "svgf", "the family of a port is not its method")


def test_command_line(csv_path, out):
    script = os.path.join(SOURCE_DIR, "eval", "charts.py")
    run = subprocess.run(["/usr/bin/python3", script, csv_path, out, "--title", "clustered"],
                         capture_output=True, text=True)
    check(run.returncode == 0, "charts.py failed: %s" % run.stderr.strip())
    names = sorted(os.listdir(out))
    for png in ["error_over_frames.png", "speed_vs_accuracy.png", "temporal_error.png"]:
        check(png in names, "charts.py wrote no %s" % png)
    check(not [n for n in names if ".tmp-" in n], "charts.py left a temporary file: %s" % names)
    run = subprocess.run(["/usr/bin/python3", script, os.path.join(out, "missing.csv"), out],
                         capture_output=True, text=True)
    lines = run.stderr.strip().splitlines()
    check(run.returncode == 1 and len(lines) == 1 and lines[0].startswith("charts.py: error: "),
          "a missing csv gave status %d and %r, not one error line" % (run.returncode, run.stderr))


def main():
    with tempfile.TemporaryDirectory(prefix="rtdr_charts_test_") as tmp:
        csv_path = os.path.join(tmp, "metrics.csv")
        write_csv(csv_path)
        test_placement(csv_path, tmp)
        test_styles()
        out = os.path.join(tmp, "cli")
        os.mkdir(out)
        test_command_line(csv_path, out)
    for what in failures:
        print("eval_charts_test: " + what)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
