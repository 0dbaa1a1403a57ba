#!/usr/bin/python3
"""eval/charts.py's charts stay readable where points cluster (ctest: `eval_charts`).

Usage: eval_charts_test.py [SOURCE_DIR]   (default: the folder above this script's)

It writes metrics.csv files in the columns `rtdr eval` writes and draws the charts with charts.py's own
functions, then checks on each figure as saved, in display coordinates with the renderer's text extents:

  Two cases: `clustered` (21 settings as the SVGF sweeps and pillars cluster them: seven within 1% of svgf's
  default in time and error, the two ports within 1% of each other) and `crowded` (20 methods, 18 of whose
  times and metrics all lie within 0.4% of each other, one tight cluster beside two far points). On every panel of speed_vs_accuracy.png (one per metric):
  1. the x axis has at least 3 labelled ticks, inside its limits, and no two print alike;
  2. every point has its label; no two labels intersect; every label lies inside its axes; none covers a marker;
  3. each label's nearest marker is its own, or a leader line joins it to its own point: from the marker's
     edge (within 2 px of it) to the label box's edge (within 2 px);
  4. the legend lies outside every panel (it covers no data region), and inside the figure;
  5. each panel's dashed front is that metric's Pareto front (SSIM: higher is better);
  6. the same csv gives the same placement (place_labels is deterministic);
  7. the clustered csv is hard enough: labels at the old fixed offset (5, 4) points would overlap.
  Then:
  8. the known families have distinct colours and distinct markers, and families charts.py does not know get
     pairs that differ from those and from each other, in order of first appearance;
  9. temporal_error.png draws the reference's own change (column ref_temporal_error) beside the methods, and
     its legend and error_over_frames.png's lie outside their panels;
  10. strip.png: the auto crop is the window where the tiles differ, every tile is labelled (a title each, the
      label as given), the grid is as many columns as rows or one more, and a crop outside the frame is refused;
  11. the command line writes the four PNGs and no temporary file, with a title and tile labels that hold TeX
      (`$\\sqrt$`), shown literally; a missing csv gives one line, "charts.py: error: ...", and status 1.

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
import numpy as np  # noqa: E402
import strip  # noqa: E402

# (method, params, mean ms per frame, mean RMSE): the svgf sweeps around the default at (12.0, 0.0500).
CLUSTERED = [
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
# 20 methods: 18 within 0.4% of each other in time and in every metric, in a scrambled order, and two far from
# them (so that the 18 make one tight cluster on the chart).
CROWDED = [("m%02d" % k if k % 3 else "svgf", "" if k % 3 else "atrous_levels=%d" % k,
            12.0 * (1 + 0.0002 * ((7 * k) % 20)), 0.05 * (1 + 0.0002 * ((11 * k) % 20))) for k in range(18)] + \
          [("accum", "", 0.5, 0.120), ("none", "", 0.01, 0.200)]
FRAMES = 3
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def metric_values(k, rmse):
    """SSIM and FLIP of setting k, not in RMSE's order, so that the three fronts differ."""
    return 0.8 + 0.001 * ((5 * k) % 7) + rmse, 0.2 - 0.0005 * ((3 * k) % 5) + rmse


def write_csv(path, settings, reference=True):
    """The columns `rtdr eval` writes; frame f of a setting is off its mean by (f - 1) percent."""
    columns = ["method", "params", "frame", "rmse", "relmse", "ssim", "flip", "temporal_error",
               "ref_temporal_error", "brightness_error", "ms_total", "ms_atrous"]
    if not reference:
        columns.remove("ref_temporal_error")
    with open(path, "w", newline="") as f:
        out = csv.DictWriter(f, columns, extrasaction="ignore")
        out.writeheader()
        for k, (method, params, ms, rmse) in enumerate(settings):
            ssim, flip = metric_values(k, rmse)
            for frame in range(FRAMES):
                s = 1 + (frame - 1) / 100
                out.writerow({"method": method, "params": params, "frame": frame, "rmse": rmse * s,
                              "relmse": 2 * rmse, "ssim": ssim * s, "flip": flip * s, "brightness_error": 0.1,
                              "temporal_error": "nan" if frame == 0 else 0.005 * s,
                              "ref_temporal_error": "nan" if frame == 0 else 0.002, "ms_total": ms * s,
                              "ms_atrous": ms / 2})


def intersect(a, b):
    return min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1])


def within(a, outer):
    return a[0] >= outer[0] and a[1] >= outer[1] and a[2] <= outer[2] and a[3] <= outer[3]


def box_point_distance(box, p):
    return math.hypot(max(box[0] - p[0], 0, p[0] - box[2]), max(box[1] - p[1], 0, p[1] - box[3]))


def measure(fig):
    """What the saved figure shows, per panel: label boxes and texts by index, marker centres, leader ends,
    the front's points, the ticks; and the legends' and the figure's boxes."""
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    panels = []
    for ax in fig.axes:
        labels = {int(t.get_gid().split(":")[1]): (tuple(t.get_window_extent(renderer).extents), t.get_text())
                  for t in ax.texts if (t.get_gid() or "").startswith("label:")}
        markers = ax.transData.transform([o for c in ax.collections for o in c.get_offsets()])
        leaders = {int(line.get_gid().split(":")[1]): ax.transData.transform(np.column_stack(line.get_data()))
                   for line in ax.lines if (line.get_gid() or "").startswith("leader:")}
        fronts = [np.column_stack(line.get_data()) for line in ax.lines if line.get_linestyle() == "--"]
        lo, hi = ax.get_xlim()
        ticks = [(t.get_position()[0], t.get_text()) for t in ax.get_xticklabels() if t.get_text()]
        ticks = [(x, s) for x, s in ticks if lo <= x <= hi]
        panels.append({"axes": ax.bbox.extents, "labels": labels, "markers": markers, "leaders": leaders,
                       "fronts": fronts, "ticks": ticks, "ylabel": ax.get_ylabel(),
                       "line_labels": [line.get_label() for line in ax.lines]})
    legends = [tuple(lg.get_window_extent(renderer).extents) for lg in fig.legends]
    return {"panels": panels, "legends": legends, "figure": tuple(fig.bbox.extents), "dpi": fig.dpi}


def draw(function, *args):
    """Calls a charts.py chart function with charts.save replaced by one that measures the figure first."""
    seen = {}

    def measuring_save(fig, path):
        seen.update(measure(fig))
        real_save(fig, path)

    real_save, charts.save = charts.save, measuring_save
    try:
        function(*args)
    finally:
        charts.save = real_save
    return seen


def check_legends_outside(seen, case):
    check(seen["legends"], "%s: no legend" % case)
    for legend in seen["legends"]:
        check(within(legend, seen["figure"]), "%s: the legend leaves the figure" % case)
        for p in seen["panels"]:
            check(not intersect(legend, p["axes"]), "%s: the legend covers the data region of %s" % (case, p["ylabel"]))


def check_panel(p, settings, case, r_marker):
    where = "%s, %s" % (case, p["ylabel"].splitlines()[0])
    check(len(p["ticks"]) >= 3, "%s: %d labelled ticks on the speed axis" % (where, len(p["ticks"])))
    check(len({s for _, s in p["ticks"]}) == len(p["ticks"]), "%s: two ticks print alike: %s" % (where, p["ticks"]))
    labels, markers = p["labels"], p["markers"]
    check(sorted(t for _, t in labels.values()) == sorted(charts.label({"method": m, "params": q})
                                                          for m, q, _, _ in settings),
          "%s: the labels are not one per setting" % where)
    for (a, ta), (b, tb) in itertools.combinations(labels.values(), 2):
        check(not intersect(a, b), "%s: labels %r and %r overlap" % (where, ta, tb))
    for i, (box, text) in labels.items():
        check(within(box, p["axes"]), "%s: label %r leaves the axes" % (where, text))
        check(not any(intersect(box, (x - r_marker, y - r_marker, x + r_marker, y + r_marker)) for x, y in markers),
              "%s: label %r covers a marker" % (where, text))
        d = [box_point_distance(box, m) for m in markers]
        own_nearest = all(d[i] < d[j] for j in range(len(d)) if j != i)
        leader = p["leaders"].get(i)
        joined = leader is not None and \
            abs(math.hypot(*(leader[0] - markers[i])) - r_marker) <= 2.0 and \
            box_point_distance(box, leader[-1]) <= 2.0
        check(own_nearest or joined, "%s: label %r is nearer another point and no leader line joins it to its own"
              % (where, text))


def check_fronts(p, points, higher, case):
    """The dashed line through the panel's points is the Pareto front of (ms, value) for its metric."""
    sign = -1 if higher else 1
    expected = [q for q in points if not any(r[0] <= q[0] and sign * r[1] <= sign * q[1] and r != q for r in points)]
    drawn = p["fronts"][0] if p["fronts"] else np.zeros((0, 2))
    check(sorted(map(tuple, np.round(drawn, 9))) == sorted(map(tuple, np.round(expected, 9))),
          "%s: the front of %s is not its Pareto front" % (case, p["ylabel"].splitlines()[0]))


def test_speed_chart(settings, case, out):
    path = os.path.join(out, case + ".csv")
    write_csv(path, settings)
    groups = charts.group(charts.read_rows(path))
    styles = charts.family_styles(charts.family(name) for name in groups)
    seen = draw(charts.speed_vs_accuracy, groups, styles, out, " - " + case)
    r_marker = math.sqrt(charts.MARKER_AREA) / 2 * seen["dpi"] / 72
    check(len(seen["panels"]) == 3, "%s: %d panels, not one per metric (rmse, ssim, flip)" % (case, len(seen["panels"])))
    for p, metric in zip(seen["panels"], ["rmse", "ssim", "flip"]):
        check_panel(p, settings, case, r_marker)
        points = [(charts.mean([r["ms_total"] for r in g]), charts.mean([r[metric] for r in g])) for g in groups.values()]
        check_fronts(p, points, metric == "ssim", case)
    check_legends_outside(seen, case)
    again = draw(charts.speed_vs_accuracy, groups, styles, out, " - " + case)
    check([p["labels"] for p in again["panels"]] == [p["labels"] for p in seen["panels"]],
          "%s: a second drawing of the same csv placed the labels elsewhere" % case)
    return seen


def test_old_offset_overlaps(seen):
    """The clustered case is hard: labels at the old fixed offset of (5, 4) points would overlap."""
    p = seen["panels"][0]
    dx, dy = 5 * seen["dpi"] / 72, 4 * seen["dpi"] / 72
    old = [(x + dx, y + dy, x + dx + b[2] - b[0], y + dy + b[3] - b[1])
           for (x, y), (b, _) in zip(p["markers"], [p["labels"][i] for i in sorted(p["labels"])])]
    check(any(intersect(a, b) for a, b in itertools.combinations(old, 2)),
          "the points are not clustered enough: labels at the old fixed offset would not overlap")


def test_styles():
    known = list(charts.FAMILY_STYLES)
    for name in ["svgf", "asvgf", "eaw", "a-eaw", "accum", "none", "trmv"]:
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


def test_over_frames(out):
    path = os.path.join(out, "frames.csv")
    write_csv(path, CLUSTERED)
    groups = charts.group(charts.read_rows(path))
    styles = charts.family_styles(charts.family(name) for name in groups)
    lines = charts.line_settings(groups, "svgf,asvgf,svgf:alpha=0.1:alpha_moments=0.1,missing")
    check(lines == ["svgf", "asvgf", "svgf:alpha=0.1"], "--lines chose %s" % lines)
    seen = draw(charts.over_frames, groups, styles, ["temporal_error"], lines, "t.png", out, "", "ref_temporal_error")
    drawn = seen["panels"][0]["line_labels"]
    check(any(s.startswith("reference") for s in drawn), "temporal_error.png has no reference curve: %s" % drawn)
    check(len(drawn) == len(lines) + 1, "temporal_error.png draws %s, not the --lines and the reference" % drawn)
    check_legends_outside(seen, "temporal_error.png")
    seen = draw(charts.over_frames, groups, styles, ["rmse", "ssim", "flip"], lines, "e.png", out, "")
    check(len(seen["panels"]) == 3, "error_over_frames.png has %d panels, not 3" % len(seen["panels"]))
    check_legends_outside(seen, "error_over_frames.png")


def test_strip(out):
    """Tiles that agree everywhere but in one 40x20 window of a 160x90 frame: the auto crop must hold it."""
    rng = np.random.default_rng(1)
    base = rng.random((90, 160, 3)) * 0.1
    tiles = []
    for k, name in enumerate(["1 spp input", "svgf", "asvgf:backend=vulkan", "$\\sqrt$", "trmv", "reference"]):
        image = base.copy()
        image[50:70, 100:140] += 0.15 * k  # the methods differ here only
        if k == 0:
            image = rng.random((90, 160, 3))  # the input's noise, everywhere: it must not choose the window
        path = os.path.join(out, "tile%d.png" % k)
        import matplotlib.image as mpimg
        mpimg.imsave(path, np.clip(image, 0, 1))
        tiles.append((name, path))
    images = [mpimg.imread(p)[..., :3] for _, p in tiles]
    (x, y, w, h), overview = strip.choose_crop("auto", tiles, images)
    check((w, h) == (80, 45) and overview, "the auto crop is %dx%d, not half the frame, 80x45" % (w, h))
    check(x <= 100 and x + w >= 140 and y <= 50 and y + h >= 70,
          "the auto crop (%d, %d, %d, %d) misses the window where the methods differ" % (x, y, w, h))
    seen = {}

    def measuring_save(fig, path):
        seen["titles"] = [ax.get_title() for ax in fig.axes if ax.get_title()]
        seen["grid"] = fig.axes[0].get_subplotspec().get_gridspec().get_geometry()
        fig.canvas.draw()  # TeX in a title would raise here
        charts.save(fig, path)

    strip.draw_strip(tiles, "auto", os.path.join(out, "strip.png"), "", measuring_save, charts.DPI)
    check(seen["titles"][1:] == [strip.literal(n) for n, _ in tiles], "strip tiles labelled %s" % seen["titles"])
    rows, cols = seen["grid"]
    check(cols in (rows, rows + 1) and rows * cols >= len(tiles) + 1, "strip grid of %dx%d" % (cols, rows))
    try:
        strip.choose_crop(strip.parse_crop("150,0,20,10"), tiles, images)
        check(False, "a crop outside the frame was accepted")
    except ValueError:
        pass


def test_command_line(out):
    csv_path = os.path.join(out, "metrics.csv")
    write_csv(csv_path, CLUSTERED)
    tile = os.path.join(out, "tile.png")
    import matplotlib.image as mpimg
    mpimg.imsave(tile, np.full((18, 32, 3), 0.5))
    script = os.path.join(SOURCE_DIR, "eval", "charts.py")
    run = subprocess.run(["/usr/bin/python3", script, csv_path, out, "--title", "$\\sqrt$", "--tile", "$\\sqrt$.gltf",
                          tile, "--tile", "reference", tile], capture_output=True, text=True)
    check(run.returncode == 0, "charts.py failed on a TeX title: %s" % run.stderr.strip())
    names = sorted(os.listdir(out))
    for png in ["error_over_frames.png", "speed_vs_accuracy.png", "temporal_error.png", "strip.png"]:
        check(png in names, "charts.py wrote no %s" % png)
    check(not [n for n in names if ".tmp-" in n], "charts.py left a temporary file: %s" % names)
    run = subprocess.run(["/usr/bin/python3", script, os.path.join(out, "missing.csv"), out],
                         capture_output=True, text=True)
    lines = run.stderr.strip().splitlines()
    check(run.returncode == 1 and len(lines) == 1 and lines[0].startswith("charts.py: error: "),
          "a missing csv gave status %d and %r, not one error line" % (run.returncode, run.stderr))


def main():
    with tempfile.TemporaryDirectory(prefix="rtdr_charts_test_") as tmp:
        seen = test_speed_chart(CLUSTERED, "clustered", tmp)
        test_old_offset_overlaps(seen)
        test_speed_chart(CROWDED, "crowded", tmp)
        test_styles()
        test_over_frames(tmp)
        test_strip(tmp)
        out = os.path.join(tmp, "cli")
        os.mkdir(out)
        test_command_line(out)
    for what in failures:
        print("eval_charts_test: " + what)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
