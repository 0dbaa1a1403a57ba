#!/usr/bin/python3
"""Report side of tools/compare_cycles.sh: RTDR's frame against Cycles' render, mean RGB ratio and a map of
per-block ratios.

    /usr/bin/python3 tools/compare_cycles_report.py RTDR.exr CYCLES.exr [BLOCKS]

RTDR's radiance is recombined from its layers as `rtdr render` defines it (trace/README.md):
emission + max(albedo, 0.001) (direct + indirect). Cycles' is its R, G, B. Ratios are RTDR / Cycles.
The block map splits the image into BLOCKS x BLOCKS (default 4) and prints each block's ratio of mean
luminance (Rec. 709 weights), top row first.
"""
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit("compare_cycles: cannot read " + path)
    names = list(image.spec().channelnames)
    pixels = image.read_image(format="float")
    image.close()
    return names, np.asarray(pixels)


def layer(names, pixels, prefix):
    return np.stack([pixels[:, :, names.index(prefix + c)] for c in ("R", "G", "B")], axis=2)


def main():
    rtdr_path, cycles_path = sys.argv[1], sys.argv[2]
    blocks = int(sys.argv[3]) if len(sys.argv) > 3 else 4
    names, pixels = read(rtdr_path)
    albedo = np.maximum(layer(names, pixels, "albedo."), 0.001)
    rtdr = layer(names, pixels, "emission.") + albedo * (layer(names, pixels, "direct.") + layer(names, pixels, "indirect."))
    names, pixels = read(cycles_path)
    cycles = layer(names, pixels, "")
    if rtdr.shape != cycles.shape:
        sys.exit("compare_cycles: sizes differ: %s and %s" % (rtdr.shape, cycles.shape))
    mean_rtdr, mean_cycles = rtdr.mean(axis=(0, 1)), cycles.mean(axis=(0, 1))
    print("mean RGB   RTDR   %.5f %.5f %.5f" % tuple(mean_rtdr))
    print("mean RGB   Cycles %.5f %.5f %.5f" % tuple(mean_cycles))
    print("mean RGB ratio RTDR / Cycles: %.4f %.4f %.4f" % tuple(mean_rtdr / mean_cycles))
    weights = np.array([0.2126, 0.7152, 0.0722])
    lum_rtdr, lum_cycles = rtdr @ weights, cycles @ weights
    h, w = lum_rtdr.shape
    print("per-block luminance ratio (%d x %d blocks, top row first):" % (blocks, blocks))
    for by in range(blocks):
        row = []
        for bx in range(blocks):
            ys = slice(by * h // blocks, (by + 1) * h // blocks)
            xs = slice(bx * w // blocks, (bx + 1) * w // blocks)
            c = lum_cycles[ys, xs].mean()
            row.append("%7.4f" % (lum_rtdr[ys, xs].mean() / c) if c > 0 else "    n/a")
        print("  " + " ".join(row))


if __name__ == "__main__":
    main()
