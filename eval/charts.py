#!/usr/bin/python3
"""The three charts of an evaluation, from the metrics.csv that `rtdr eval` writes.

  speed_vs_accuracy.png  mean ms per frame against mean RMSE (linear HDR), one labelled point per method and
                         parameter setting, the Pareto front (nothing both faster and more accurate) marked
  error_over_frames.png  RMSE per frame for each method's default setting (in the style of A-SVGF Fig. 4)
  temporal_error.png     temporal error per frame: mean luminance of the difference of consecutive display
                         frames (SVGF Sec. 5.4, in the style of SVGF Fig. 10)

A method's family is its name before the first ':' (svgf, asvgf, eaw, a-eaw, accum, none, ...). Each family
has one colour and one marker, the same on all three charts (FAMILY_STYLES; a family not listed there takes
the next pair of a fixed cycle, in the order the csv first names it), and the speed chart's legend lists
them. The shader ports (backend=vulkan, at their device time) keep their family's colour and marker, drawn
open (white inside).

Where points cluster, each label is placed apart by place_labels: candidate positions on rings around its
point, chosen greedily so that no two labels overlap, no label covers a marker, and every label stays inside
the axes (measured in display coordinates with the renderer's text extents); a label that had to move away
from its point is joined to it by a thin leader line. The placement is deterministic: the same csv gives
the same chart. tests/eval_charts_test.py checks it on clustered points.

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
    import matplotlib.patheffects as patheffects
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.lines import Line2D
except ImportError as e:  # one line, as below
    sys.exit("charts.py: error: %s (needs Debian's python3-matplotlib: run tools/setup.sh)" % e)

DPI = 110  # figures are laid out and saved at one resolution, so the measured label boxes are the saved ones

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
}
# Families not listed above take colour i % 7 and marker i % 6 of these; 7 and 6 are coprime, so the first
# 42 such families all get a different pair.
OTHER_COLOURS = ["tab:green", "tab:cyan", "#393b79", "#8c6d31", "#843c39", "#7b4173", "#637939"]
OTHER_MARKERS = [">", "p", "d", "8", "H", "*"]

MARKER_AREA = 36  # scatter marker area [pt^2]
LABEL_FONTSIZE = 7
LABEL_GAP_PX = 3.0  # free space kept between a label and a marker, another label or the axes' frame


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
        fig.savefig(tmp, dpi=DPI, format="png")
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


# Label placement. Everything below works in display coordinates (pixels), on boxes (x0, y0, x1, y1).


def overlap_area(boxes, others):
    """The area of the intersection of each of `boxes` (N x 4) with each of `others` (M x 4): N x M."""
    w = np.minimum(boxes[:, None, 2], others[None, :, 2]) - np.maximum(boxes[:, None, 0], others[None, :, 0])
    h = np.minimum(boxes[:, None, 3], others[None, :, 3]) - np.maximum(boxes[:, None, 1], others[None, :, 1])
    return np.clip(w, 0, None) * np.clip(h, 0, None)


def inside(points, boxes):
    """Whether each of `points` (... x 2) lies strictly inside each of `boxes` (M x 4): ... x M."""
    x, y = points[..., 0, None], points[..., 1, None]
    return (x > boxes[:, 0]) & (x < boxes[:, 2]) & (y > boxes[:, 1]) & (y < boxes[:, 3])


def sample_polyline(xy, step=2.0):
    """Points every `step` pixels or closer along the polyline through the rows of `xy` (K x 2)."""
    samples = [np.zeros((0, 2))]
    for a, b in zip(xy[:-1], xy[1:]):
        n = max(2, int(np.hypot(*(b - a)) / step) + 1)
        samples.append(a + np.linspace(0.0, 1.0, n)[:, None] * (b - a))
    return np.concatenate(samples)


def label_candidates(p, size, r_first, r_last, step):
    """Candidate boxes of size (w, h) on rings around point p: boxes (N x 4), anchors (N x 2), radii (N).

    On the ring of radius rho, in direction theta, the box touches the ring at its anchor, the point of its
    boundary that faces p: theta = 0 puts the middle of its left edge at distance rho right of p, theta = 45
    degrees its lower-left corner. Nearer rings come first and, on a ring, the directions go right, upper
    right, up, ... counter-clockwise, so that a tie goes to the usual position, right of the point."""
    w, h = size
    theta = np.radians(np.arange(16) * 22.5)
    c, s = np.cos(theta), np.sin(theta)
    square = np.maximum(np.abs(c), np.abs(s))
    fx, fy = 0.5 - 0.5 * c / square, 0.5 - 0.5 * s / square  # the anchor, as fractions of w and h
    rho = np.arange(r_first, r_last + step, step)
    rho, c, s, fx, fy = [a.ravel() for a in np.broadcast_arrays(rho[:, None], c, s, fx, fy)]
    anchors = np.column_stack([p[0] + rho * c, p[1] + rho * s])
    lower_left = anchors - np.column_stack([fx * w, fy * h])
    return np.column_stack([lower_left, lower_left + (w, h)]), anchors, rho


def label_costs(boxes, anchors, rho, p, own, scene):
    """The cost of each candidate box of point p (marker number `own`). In order of weight: leaving the axes;
    covering a marker or a label (per pixel of overlap, the gap included); a leader line over another marker or
    label (each); covering the lines to avoid and the leader lines (per 2-pixel sample); distance (per pixel)."""
    x0, y0, x1, y1 = scene["frame"]
    outside = (boxes[:, 0] < x0) | (boxes[:, 1] < y0) | (boxes[:, 2] > x1) | (boxes[:, 3] > y1)
    padded = boxes + (-LABEL_GAP_PX, -LABEL_GAP_PX, LABEL_GAP_PX, LABEL_GAP_PX)
    covered = overlap_area(padded, np.vstack([scene["markers"], scene["labels"]])).sum(axis=1)
    others = np.vstack([np.delete(scene["markers"], own, axis=0), scene["labels"]])
    leader = p + np.linspace(0.0, 1.0, 12)[None, :, None] * (anchors[:, None, :] - p)  # N x 12 x 2
    crossed = inside(leader, others).any(axis=1).sum(axis=1)
    on_lines = inside(np.vstack(scene["lines"]), boxes).sum(axis=0)
    return 1e9 * outside + 1e3 * covered + 50.0 * crossed + 2.0 * on_lines + rho


def place_labels(ax, points, labels, colours=None, lines=()):
    """Writes labels[i] beside points[i] (data coordinates) on `ax` and returns the text artists.

    Call it last, after the layout (tight_layout) and the scales are final: it fixes the axes' limits and
    places in pixels. The most crowded points (most neighbours within 40 px) choose first; each label takes
    its cheapest candidate (label_candidates, label_costs), so no two labels overlap, none covers a marker and
    all stay inside the axes wherever the axes have room. A label more than half a line's height further
    than the nearest ring gets a leader line from its point, in colours[i] (grey by default). `lines` are
    polylines, (xs, ys) in data coordinates, that labels should not cover where they can avoid it (the
    Pareto front)."""
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    ax.set_xlim(ax.get_xlim())  # from here on, a pixel is a fixed place in the data
    ax.set_ylim(ax.get_ylim())
    to_px, to_data = ax.transData, ax.transData.inverted()
    xy = to_px.transform(np.asarray(points, float).reshape(-1, 2))
    r_marker = math.sqrt(MARKER_AREA) / 2 * fig.dpi / 72 + 1  # half the marker's side, and its edge
    frame = ax.bbox.extents + (LABEL_GAP_PX, LABEL_GAP_PX, -LABEL_GAP_PX, -LABEL_GAP_PX)
    scene = {"frame": frame, "markers": np.column_stack([xy - r_marker, xy + r_marker]),
             "labels": np.zeros((0, 4)), "lines": [np.zeros((0, 2))]}
    scene["lines"] += [sample_polyline(to_px.transform(np.column_stack(line))) for line in lines]
    texts = [ax.text(0, 0, s, fontsize=LABEL_FONTSIZE, ha="left", va="bottom", zorder=4,
                     path_effects=[patheffects.withStroke(linewidth=2, foreground="white")]) for s in labels]
    crowd = (np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1)) < 40).sum(axis=1)
    r_last = math.hypot(frame[2] - frame[0], frame[3] - frame[1])
    for i in sorted(range(len(texts)), key=lambda i: (-crowd[i], i)):
        extent = texts[i].get_window_extent(renderer)
        r_first = r_marker + LABEL_GAP_PX
        boxes, anchors, rho = label_candidates(xy[i], (extent.width, extent.height), r_first, r_last, 4.0)
        best = int(np.argmin(label_costs(boxes, anchors, rho, xy[i], i, scene)))
        texts[i].set_position(to_data.transform(boxes[best, :2]))
        scene["labels"] = np.vstack([scene["labels"], boxes[best]])
        if rho[best] > r_first + extent.height / 2:
            start = xy[i] + r_marker * (anchors[best] - xy[i]) / rho[best]
            scene["lines"].append(sample_polyline(np.array([start, anchors[best]])))
            leader = to_data.transform(np.array([start, anchors[best]]))
            colour = colours[i] if colours else "0.4"
            ax.plot(leader[:, 0], leader[:, 1], color=colour, lw=0.6, alpha=0.8, zorder=2.5)
    return texts


def speed_vs_accuracy(groups, styles, out, title):
    points = [(mean([r["ms_total"] for r in g]), mean([r["rmse"] for r in g]), name) for name, g in groups.items()]
    points = [p for p in points if math.isfinite(p[0]) and math.isfinite(p[1])]  # a method that never ran
    fig, ax = plt.subplots(figsize=(10, 6.5), dpi=DPI)
    for ms, err, name in points:
        colour, marker = styles[family(name)]
        face = "white" if is_port(name) else colour  # the shader ports: open markers, at their device time
        ax.scatter(ms, err, s=MARKER_AREA, marker=marker, facecolors=face, edgecolors=colour, linewidths=1.2,
                   zorder=3)
    front = pareto_front(points)
    ax.plot([p[0] for p in front], [p[1] for p in front], "k--", lw=1, zorder=2)
    ax.set_xscale("symlog", linthresh=1.0)
    ax.margins(0.08)
    ax.set_xlabel("mean time per frame [ms] (golden passes: wall time; backend=vulkan: device time)")
    ax.set_ylabel("mean RMSE against the reference (linear HDR)")
    ax.set_title("Speed versus accuracy" + title)
    ax.grid(True, alpha=0.3)
    ax.legend(handles=legend_handles(points, styles), loc="upper left", bbox_to_anchor=(1.02, 1.0),
              borderaxespad=0.0, fontsize=8)
    fig.tight_layout()
    place_labels(ax, [p[:2] for p in points], [p[2] for p in points],
                 colours=[styles[family(p[2])][0] for p in points],
                 lines=[([p[0] for p in front], [p[1] for p in front])])
    save(fig, os.path.join(out, "speed_vs_accuracy.png"))


def legend_handles(points, styles):
    """One entry per family on the chart, in the order of `styles`, then the ports' open marker and the front."""
    shown = {family(p[2]) for p in points}
    handles = [Line2D([], [], ls="", marker=m, color=c, label=f) for f, (c, m) in styles.items() if f in shown]
    if any(is_port(p[2]) for p in points):
        handles.append(Line2D([], [], ls="", marker="o", mfc="white", mec="0.3", mew=1.2,
                              label="open: backend=vulkan\n(shader port, device time)"))
    handles.append(Line2D([], [], color="k", ls="--", lw=1, label="Pareto front"))
    return handles


def over_frames(groups, styles, key, ylabel, name, out, title):
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=DPI)
    for method, g in groups.items():
        if ":" in method:  # parameter sweeps only on the speed chart
            continue
        colour, marker = styles[family(method)]
        ax.plot([r["frame"] for r in g], [r[key] for r in g], color=colour, marker=marker, ms=4, label=method)
    ax.set_xlabel("frame")
    ax.set_ylabel(ylabel)
    ax.set_yscale("log")
    ax.set_title(ylabel + title)
    ax.grid(True, alpha=0.3)
    if ax.lines:  # a csv of sweeps only has no default setting to draw
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
    styles = family_styles(family(name) for name in groups)
    title = " - " + args.title if args.title else ""
    speed_vs_accuracy(groups, styles, args.out, title)
    over_frames(groups, styles, "rmse", "RMSE (linear HDR)", "error_over_frames.png", args.out, title)
    over_frames(groups, styles, "temporal_error", "temporal error (display)", "temporal_error.png", args.out, title)


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # one line for rtdr eval to quote, not a traceback
        sys.exit("charts.py: error: %s: %s" % (type(e).__name__, e))
