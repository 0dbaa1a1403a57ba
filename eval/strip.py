"""strip.png of eval/charts.py: the last frame of every method, as a labelled grid of crops.

`rtdr eval` writes each method's last display frame as a PNG (in a temporary folder) and hands charts.py the
tiles in order, each with its label: the 1-spp input, every method that ran (up to the number it is given, or
those it is asked for), the reference. The grid is about as wide as tall, so it stays readable when shrunk to a screen, and
every tile shows the same crop, magnified with visible pixels:
  auto      the half-width, half-height window where the methods differ most from each other: the largest sum
            of the per-pixel standard deviation, across the methods and the reference, of display luminance
            (the 1-spp input is left out: its noise would choose the window); the whole frame, the crop
            outlined on the last tile (the reference), comes first, so the window can be found
  full      the whole frame
  X,Y,W,H   this window, in pixels of the frame (0,0 the top left)
Labels are the user's text, shown literally (chart_layout.literal).
"""
import math

import matplotlib.image as mpimg
import matplotlib.patches as patches
import matplotlib.pyplot as plt
import numpy as np

from chart_layout import literal


def parse_crop(text):
    """'auto', 'full', or (x, y, w, h) from 'X,Y,W,H' (whole numbers, w and h at least 1)."""
    if text in ("auto", "full"):
        return text
    parts = text.split(",")
    if len(parts) != 4 or not all(p.isdigit() for p in parts) or int(parts[2]) < 1 or int(parts[3]) < 1:
        raise ValueError("--crop '%s' is not auto, full or X,Y,W,H (whole numbers, W and H at least 1)" % text)
    return tuple(int(p) for p in parts)


def luminance(image):
    """Rec. 709 luminance of an RGB(A) image in [0, 1]."""
    return image[..., 0] * 0.2126 + image[..., 1] * 0.7152 + image[..., 2] * 0.0722


def window_sums(values, w, h):
    """The sum of `values` (H x W) over every w x h window, indexed by its top-left pixel: (H-h+1) x (W-w+1)."""
    s = np.pad(values.cumsum(axis=0).cumsum(axis=1), ((1, 0), (1, 0)))
    return s[h:, w:] - s[:-h, w:] - s[h:, :-w] + s[:-h, :-w]


def auto_crop(images):
    """The half-size window (x, y, w, h) where `images` differ most (module docstring, auto)."""
    height, width = images[0].shape[:2]
    w, h = max(1, width // 2), max(1, height // 2)
    spread = np.std(np.stack([luminance(i) for i in images]), axis=0) if len(images) > 1 else np.zeros((height, width))
    sums = window_sums(spread, w, h)
    y, x = np.unravel_index(int(np.argmax(sums)), sums.shape)  # the first of equal windows: deterministic
    return int(x), int(y), w, h


def choose_crop(crop, tiles, images):
    """The crop as (x, y, w, h) inside the frame, and whether to show the whole frame first."""
    height, width = images[0].shape[:2]
    if crop == "full":
        return (0, 0, width, height), False
    if crop == "auto":
        compared = [img for (name, _), img in zip(tiles, images) if not name.startswith("1 spp input")]
        return auto_crop(compared or images), True
    x, y, w, h = crop
    if x + w > width or y + h > height:
        raise ValueError("--crop %d,%d,%d,%d reaches outside the %dx%d frame" % (x, y, w, h, width, height))
    return crop, (w, h) != (width, height)


def grid_shape(n):
    """Columns and rows for n tiles: one row up to 4, then about as many columns as rows."""
    cols = n if n <= 4 else math.ceil(math.sqrt(n))
    return cols, math.ceil(n / cols)


def draw_strip(tiles, crop, path, title, save, dpi):
    """Writes `path`: tiles [(label, png path)] as a labelled grid of `crop` (parse_crop), with save(fig, path)."""
    images = [mpimg.imread(p)[..., :3] for _, p in tiles]
    shapes = {img.shape[:2] for img in images}
    if len(shapes) != 1:
        raise ValueError("the strip's tiles differ in size: %s" % sorted(shapes))
    (x, y, w, h), overview = choose_crop(crop, tiles, images)
    height, width = images[0].shape[:2]
    whole = ("whole frame (%s), the crop outlined" % tiles[-1][0], images[-1], True)  # the reference, in rtdr eval
    panels = ([whole] if overview else []) + \
             [(name, img, False) for (name, _), img in zip(tiles, images)]
    cols, rows = grid_shape(len(panels))
    tile_w = 3.2  # inches per tile
    tile_h = tile_w * h / w
    fig, axes = plt.subplots(rows, cols, figsize=(cols * tile_w, rows * (tile_h + 0.35) + 0.5), dpi=dpi,
                             squeeze=False)
    for ax in axes.ravel():
        ax.axis("off")
    for ax, (name, img, whole) in zip(axes.ravel(), panels):
        if whole:
            ax.imshow(img, interpolation="antialiased")  # the whole frame, shrunk
            ax.add_patch(patches.Rectangle((x - 0.5, y - 0.5), w, h, fill=False, ec="yellow", lw=1.5))
        else:
            ax.imshow(img[y:y + h, x:x + w], interpolation="nearest")
        ax.set_title(literal(name), fontsize=9)
    fig.suptitle(literal("Last frame%s: crop of %dx%d at (%d, %d) in the %dx%d frame" %
                         (title, w, h, x, y, width, height)), fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.4 / fig.get_figheight()))
    save(fig, path)
