"""Layout helpers of eval/charts.py: literal text, readable millisecond ticks, a legend outside the plots, and
labels placed beside their points without ambiguity.

Literal text. Method specs, scene names and file names are the user's text, never markup: matplotlib reads a
string with two '$' as mathtext (and with text.usetex as TeX), so a scene named `$\\sqrt$.gltf` would fail
after all the rendering. literal() escapes every '$'; usetex is switched off where matplotlib is imported.

Ticks. The speed axis is logarithmic (methods differ by orders of magnitude). ms_ticks labels the 1-2-5 values
inside the axis' limits, thinned to 1-per-decade when there are too many; when fewer than three of those fall
inside (all methods within a few percent of each other), it labels evenly spaced values instead, with as many
decimals as keep them distinct.

Labels. place_labels puts labels[i] beside points[i]: candidate boxes on rings around each point, chosen
greedily (the most crowded points first) so that no two labels overlap, no label covers a marker, every label
stays inside its axes, and a label's nearest marker is its own. Where a label must sit nearer to another point
than to its own, or further than the nearest ring, a leader line joins it to its point: from the marker's edge
to the box's edge, in the point's colour, tagged gid "leader:<i>" (tests/eval_charts_test.py finds it by
that). Everything is measured in display coordinates with the renderer's text extents, so the placement is
what the saved PNG shows, and deterministic: the same points give the same chart.
"""
import math

import matplotlib.patheffects as patheffects
import numpy as np
from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

MARKER_AREA = 36  # scatter marker area [pt^2]
LABEL_FONTSIZE = 7
LABEL_GAP_PX = 3.0  # free space kept between a label and a marker, another label or the axes' frame


def literal(text):
    """`text` as matplotlib shows it literally: every '$' escaped, so no mathtext is parsed."""
    return str(text).replace("$", r"\$")


# Ticks.


def decimals_to_tell_apart(values):
    """The fewest decimals (0-6) with which every value of `values` prints differently."""
    for d in range(7):
        if len({"%.*f" % (d, v) for v in values}) == len(values):
            return d
    return 6


def ms_ticks(lo, hi, most=8):
    """At least three readable tick values [ms] inside [lo, hi] (lo > 0) for a logarithmic axis."""
    decades = range(int(math.floor(math.log10(lo))), int(math.ceil(math.log10(hi))) + 1)
    ticks = [m * 10.0 ** d for d in decades for m in (1, 2, 5) if lo <= m * 10.0 ** d <= hi]
    if len(ticks) > most:
        ticks = [t for t in ticks if abs(math.log10(t) - round(math.log10(t))) < 1e-9]
    if len(ticks) >= 3:
        return ticks
    return list(np.linspace(lo, hi, 6)[1:-1])  # near-equal times: four evenly spaced values


def set_ms_axis(ax, xs):
    """A logarithmic x axis over the times `xs` [ms] with the ticks of ms_ticks, labelled in plain numbers."""
    positive = [x for x in xs if x > 0]
    lo, hi = (min(positive), max(positive)) if positive else (1.0, 1.0)
    if hi <= lo * 1.0001:  # a single time: give it a range to sit in
        lo, hi = lo * 0.9, hi * 1.1
    span = math.log10(hi / lo)
    lo, hi = lo / 10 ** (0.08 * span), hi * 10 ** (0.08 * span)  # a margin on each side, as ax.margins
    ax.set_xscale("log")
    ax.set_xlim(lo, hi)
    ticks = ms_ticks(lo, hi)
    d = decimals_to_tell_apart(ticks) if max(ticks) / min(ticks) < 10 else None
    ax.xaxis.set_major_locator(FixedLocator(ticks))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: "%.*f" % (d, v) if d is not None else "%g" % v))


def legend_outside(fig, handles, anchor_ax, fontsize=8):
    """A legend right of all plots, level with the top of `anchor_ax`; the plots are laid out (tight_layout) in
    the room left of it. Call after the axes are drawn and before labels are placed (it moves the axes)."""
    legend = fig.legend(handles=handles, loc="upper left", fontsize=fontsize, borderaxespad=0.0,
                        bbox_to_anchor=(0.0, 1.0), frameon=True)
    for text in legend.get_texts():
        text.set_text(literal(text.get_text()))
    renderer = fig.canvas.get_renderer()
    width = legend.get_window_extent(renderer).width / fig.bbox.width
    right = 1.0 - width - 0.03
    fig.tight_layout(rect=(0.0, 0.0, right, 1.0))
    top = anchor_ax.get_position().y1
    legend.set_bbox_to_anchor((right + 0.015, top), transform=fig.transFigure)
    return legend


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


def box_distance(boxes, points):
    """The distance from each of `boxes` (N x 4) to each of `points` (M x 2): N x M (0 inside)."""
    dx = np.maximum.reduce([boxes[:, None, 0] - points[None, :, 0], np.zeros((len(boxes), len(points))),
                            points[None, :, 0] - boxes[:, None, 2]])
    dy = np.maximum.reduce([boxes[:, None, 1] - points[None, :, 1], np.zeros((len(boxes), len(points))),
                            points[None, :, 1] - boxes[:, None, 3]])
    return np.hypot(dx, dy)


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
    label (each); sitting nearer to another point than to its own (then it needs a leader line); covering the
    lines to avoid and the leader lines (per 2-pixel sample); distance (per pixel)."""
    x0, y0, x1, y1 = scene["frame"]
    outside = (boxes[:, 0] < x0) | (boxes[:, 1] < y0) | (boxes[:, 2] > x1) | (boxes[:, 3] > y1)
    padded = boxes + (-LABEL_GAP_PX, -LABEL_GAP_PX, LABEL_GAP_PX, LABEL_GAP_PX)
    covered = overlap_area(padded, np.vstack([scene["markers"], scene["labels"]])).sum(axis=1)
    others = np.vstack([np.delete(scene["markers"], own, axis=0), scene["labels"]])
    leader = p + np.linspace(0.0, 1.0, 12)[None, :, None] * (anchors[:, None, :] - p)  # N x 12 x 2
    crossed = inside(leader, others).any(axis=1).sum(axis=1)
    ambiguous = nearest_is_other(boxes, scene["points"], own)
    on_lines = inside(np.vstack(scene["lines"]), boxes).sum(axis=0)
    return 1e9 * outside + 1e3 * covered + 50.0 * crossed + 40.0 * ambiguous + 2.0 * on_lines + rho


def nearest_is_other(boxes, points, own):
    """Whether some other point of `points` is nearer to each box than point `own` is (ties are ambiguous)."""
    d = box_distance(boxes, points)
    return (np.delete(d, own, axis=1) <= d[:, own, None]).any(axis=1) if len(points) > 1 else np.zeros(len(boxes), bool)


def place_labels(ax, points, labels, colours=None, lines=()):
    """Writes labels[i] beside points[i] (data coordinates) on `ax` and returns the text artists.

    Call it last, after the layout and the scales are final: it fixes the axes' limits and places in pixels.
    The most crowded points (most neighbours within 40 px) choose first; each label takes its cheapest candidate
    (label_candidates, label_costs). A label that sits further than the nearest ring, or nearer to another point
    than to its own, gets a leader line from its point, in colours[i] (grey by default). `lines` are polylines,
    (xs, ys) in data coordinates, that labels should not cover where they can avoid it (the Pareto front)."""
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    ax.set_xlim(ax.get_xlim())  # from here on, a pixel is a fixed place in the data
    ax.set_ylim(ax.get_ylim())
    to_px, to_data = ax.transData, ax.transData.inverted()
    xy = to_px.transform(np.asarray(points, float).reshape(-1, 2))
    r_marker = math.sqrt(MARKER_AREA) / 2 * fig.dpi / 72 + 1  # half the marker's side, and its edge
    frame = ax.bbox.extents + (LABEL_GAP_PX, LABEL_GAP_PX, -LABEL_GAP_PX, -LABEL_GAP_PX)
    scene = {"frame": frame, "points": xy, "markers": np.column_stack([xy - r_marker, xy + r_marker]),
             "labels": np.zeros((0, 4)), "lines": [np.zeros((0, 2))]}
    scene["lines"] += [sample_polyline(to_px.transform(np.column_stack(line))) for line in lines]
    texts = [ax.text(0, 0, literal(s), fontsize=LABEL_FONTSIZE, ha="left", va="bottom", zorder=4,
                     path_effects=[patheffects.withStroke(linewidth=2, foreground="white")]) for s in labels]
    crowd = (np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1)) < 40).sum(axis=1)
    r_last = math.hypot(frame[2] - frame[0], frame[3] - frame[1])
    for i in sorted(range(len(texts)), key=lambda i: (-crowd[i], i)):
        extent = texts[i].get_window_extent(renderer)
        r_first = r_marker + LABEL_GAP_PX
        boxes, anchors, rho = label_candidates(xy[i], (extent.width, extent.height), r_first, r_last, 4.0)
        best = int(np.argmin(label_costs(boxes, anchors, rho, xy[i], i, scene)))
        texts[i].set_position(to_data.transform(boxes[best, :2]))
        texts[i].set_gid("label:%d" % i)
        scene["labels"] = np.vstack([scene["labels"], boxes[best]])
        far = rho[best] > r_first + extent.height / 2
        if far or nearest_is_other(boxes[best:best + 1], xy, i)[0]:
            start = xy[i] + r_marker * (anchors[best] - xy[i]) / rho[best]
            scene["lines"].append(sample_polyline(np.array([start, anchors[best]])))
            leader = to_data.transform(np.array([start, anchors[best]]))
            colour = colours[i] if colours else "0.4"
            (line,) = ax.plot(leader[:, 0], leader[:, 1], color=colour, lw=0.7, alpha=0.9, zorder=2.5)
            line.set_gid("leader:%d" % i)
    return texts
