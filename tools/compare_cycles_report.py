#!/usr/bin/python3
"""Report side of tools/compare_cycles.sh: RTDR's frame against one or more Cycles renders, mean RGB ratio and a
map of per-block ratios for each.

    /usr/bin/python3 tools/compare_cycles_report.py RTDR.exr BLOCKS MATERIAL=CYCLES.exr [MATERIAL=CYCLES.exr]

MATERIAL names the Cycles material the render used (principled or lambert, as tools/compare_cycles_blender.py
takes it); the report prints a line on what each ratio means (EXPLANATION below; the measurements behind it are
in trace/README.md, "Differences from Cycles").
RTDR's radiance is recombined from its layers as `rtdr render` defines it (trace/README.md):
emission + max(albedo, 0.001) (direct + indirect). Cycles' is its R, G, B. Ratios are RTDR / Cycles.
The block map splits the image into BLOCKS x BLOCKS and prints each block's ratio of mean
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


EXPLANATION = {
    "principled": "against what Blender 3.4 shows (the importer's Principled BSDF v1): below 1 on diffuse "
                  "scenes, as v1 reflects more than glTF's BRDF (retro-reflection, specular added uncoupled)",
    "lambert": "against glTF's BRDF in Cycles (Lambert, the diffuse lobe, in place of each Principled BSDF): "
               "expect 1 within 3%, RTDR's albedo-scaled specular adding 1-2% at roughness 1",
}


def rtdr_radiance(path):
    """RTDR's radiance, and the pixels that are neither emitters nor next to one (where the BRDF shows)."""
    names, pixels = read(path)
    albedo = np.maximum(layer(names, pixels, "albedo."), 0.001)
    emission = layer(names, pixels, "emission.")
    emitter = emission.sum(axis=2) > 0
    near = emitter.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near |= np.roll(emitter, (dy, dx), axis=(0, 1))
    return emission + albedo * (layer(names, pixels, "direct.") + layer(names, pixels, "indirect.")), ~near


def report(rtdr, reflecting, cycles, blocks):
    mean_rtdr, mean_cycles = rtdr.mean(axis=(0, 1)), cycles.mean(axis=(0, 1))
    print("  mean RGB   RTDR   %.5f %.5f %.5f" % tuple(mean_rtdr))
    print("  mean RGB   Cycles %.5f %.5f %.5f" % tuple(mean_cycles))
    print("  mean RGB ratio RTDR / Cycles: %.4f %.4f %.4f" % tuple(mean_rtdr / mean_cycles))
    # Emitters outshine the rest, so the whole-image mean weighs them (and the pixel filter at their edges) most.
    print("  mean RGB ratio without emitters (%d of %d pixels, none next to one): %.4f %.4f %.4f" % (
        (reflecting.sum(), reflecting.size) + tuple(rtdr[reflecting].mean(axis=0) / cycles[reflecting].mean(axis=0))))
    weights = np.array([0.2126, 0.7152, 0.0722])
    lum_rtdr, lum_cycles = rtdr @ weights, cycles @ weights
    h, w = lum_rtdr.shape
    print("  per-block luminance ratio (%d x %d blocks, top row first):" % (blocks, blocks))
    for by in range(blocks):
        row = []
        for bx in range(blocks):
            ys = slice(by * h // blocks, (by + 1) * h // blocks)
            xs = slice(bx * w // blocks, (bx + 1) * w // blocks)
            c = lum_cycles[ys, xs].mean()
            row.append("%7.4f" % (lum_rtdr[ys, xs].mean() / c) if c > 0 else "    n/a")
        print("    " + " ".join(row))


def main():
    if len(sys.argv) < 4 or any("=" not in a for a in sys.argv[3:]):
        sys.exit(__doc__)
    rtdr, reflecting = rtdr_radiance(sys.argv[1])
    blocks = int(sys.argv[2])
    for argument in sys.argv[3:]:
        material, cycles_path = argument.split("=", 1)
        names, pixels = read(cycles_path)
        cycles = layer(names, pixels, "")
        if rtdr.shape != cycles.shape:
            sys.exit("compare_cycles: sizes differ: %s and %s" % (rtdr.shape, cycles.shape))
        print("Cycles material %s: %s" % (material, EXPLANATION.get(material, "")))
        report(rtdr, reflecting, cycles, blocks)


if __name__ == "__main__":
    main()
