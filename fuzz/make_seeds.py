"""Writes the seed corpora in fuzz/corpus/: a few small, valid inputs per harness, from which libFuzzer mutates.

    /usr/bin/python3 fuzz/make_seeds.py        # rewrites fuzz/corpus/*/ (the files in git come from here)

Valid seeds matter: a mutation of a valid file gets past the parser and reaches the checks behind it.
  gltf_loader_fuzz/  scenes with their buffers and images embedded (one input is a whole scene):
                     a triangle and a camera as .gltf and as .glb, and tests/data/anim_test.gltf's scene
                     (animation, textures, matrix nodes, extras), written by scenes/make_test_fixtures.py
  exr_reader_fuzz/   2x2 frames with the layers a filter reads (app/sequence.cpp), in the layouts OpenEXR
                     offers: FLOAT + UINT with ZIP (what core/exr_io.cpp writes), HALF with PIZ, tiled with
                     RLE, uncompressed with a NaN
  cli_args_fuzz/     command lines of README.md, one argument per line
Needs Debian's python3-openimageio (tools/setup.sh installs it) for the EXR files.
"""

import json
import os
import struct
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scenes"))
import make_test_fixtures  # noqa: E402  (scenes/ is not a package)
from gltf_writer import GltfBuilder  # noqa: E402

CORPUS = os.path.join(ROOT, "fuzz", "corpus")

# The float layers read_filter_input requires to be present and finite (app/sequence.cpp).
FILTER_LAYERS = ["direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B", "albedo.R",
                 "albedo.G", "albedo.B", "emission.R", "emission.G", "emission.B", "depth.Z", "depth.dX",
                 "depth.dY", "normal.X", "normal.Y", "normal.Z", "motion.X", "motion.Y"]


def write(harness, name, data):
    folder = os.path.join(CORPUS, harness)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


# --- glTF ------------------------------------------------------------------------------------------------

def triangle_scene():
    """One triangle in front of a camera: the least that load_scene accepts."""
    gltf = GltfBuilder("triangle")
    mesh = gltf.add_mesh("triangle", [gltf.primitive(positions=[(0, 0, 0), (1, 0, 0), (0, 1, 0)],
                                                     indices=[0, 1, 2])])
    gltf.add_node("triangle", mesh=mesh)
    gltf.add_node("camera", camera=gltf.add_camera("camera", yfov=0.8, znear=0.1), translation=(0, 0, 3))
    return gltf


def compact(doc):
    """JSON without white space: fewer bytes for the fuzzer to mutate uselessly."""
    return json.dumps(doc, separators=(",", ":")).encode("ascii")


def glb(gltf):
    """Binary glTF (glTF spec Sec. 4.4): a 12-byte header, a JSON chunk, a BIN chunk holding buffer 0."""
    doc = dict(gltf.doc)
    blob = bytes(gltf.blob)
    doc["buffers"] = [{"byteLength": len(blob)}]  # no uri: buffer 0 is the BIN chunk
    text = compact(doc)
    text += b" " * (-len(text) % 4)  # chunks are 4-byte aligned: JSON pads with spaces, BIN with zeros
    blob += b"\0" * (-len(blob) % 4)
    chunks = (struct.pack("<II", len(text), 0x4E4F534A) + text +  # "JSON"
              struct.pack("<II", len(blob), 0x004E4942) + blob)   # "BIN\0"
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks  # "glTF", version 2, total length


# --- EXR -------------------------------------------------------------------------------------------------

def exr(name, channels, formats, compression, tiled=False, nan_at=None):
    """A 2x2 EXR with one channel per name, each of the given OpenImageIO format ("float", "half", "uint")."""
    path = os.path.join(CORPUS, "exr_reader_fuzz", name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    spec = oiio.ImageSpec(2, 2, len(channels), oiio.FLOAT)
    spec.channelnames = channels
    spec.channelformats = [oiio.TypeDesc(f) for f in formats]
    spec.attribute("compression", compression)
    if tiled:
        spec.tile_width, spec.tile_height = 1, 1
    # Small distinct values (ids stay exact through float): pixel p, channel c holds 0.25 * p + c.
    pixels = np.array([[[0.25 * (2 * y + x) + c for c in range(len(channels))] for x in range(2)]
                       for y in range(2)], dtype=np.float32)
    if nan_at is not None:
        pixels[0, 1, channels.index(nan_at)] = np.nan
    out = oiio.ImageOutput.create(path)
    if not out or not out.open(path, spec) or not out.write_image(pixels) or not out.close():
        sys.exit("cannot write %s: %s" % (path, oiio.geterror()))


def main():
    scene = triangle_scene()
    write("gltf_loader_fuzz", "triangle.gltf", compact(scene.to_json()))
    write("gltf_loader_fuzz", "triangle.glb", glb(scene))
    write("gltf_loader_fuzz", "anim_test.gltf", compact(make_test_fixtures.anim_test()))

    ids = ["id.instance", "id.material"]
    exr("zip_float_uint.exr", FILTER_LAYERS + ids, ["float"] * len(FILTER_LAYERS) + ["uint"] * 2, "zip")
    exr("piz_half.exr", FILTER_LAYERS, ["half"] * len(FILTER_LAYERS), "piz")
    exr("rle_tiled.exr", ["direct.R", "depth.Z", "id.mesh"], ["float", "half", "uint"], "rle", tiled=True)
    exr("none_nan.exr", FILTER_LAYERS, ["float"] * len(FILTER_LAYERS), "none", nan_at="motion.X")

    commands = {
        "render.txt": "render --scene cornell --frames 0-9 --size 1280x720 --spp 4 --seed 7 --max-bounces 4 --out out/a",
        "filter.txt": "--threads 1 filter --method svgf --in out/a --out out/b --frames 2-3 --alpha 0.1 "
                      "--atrous-levels 4 --kernel-size 3 --dump-passes",
        "probe.txt": "probe --in out/a --frame 5 --pixel 640,360 --pass atrous --level 2 --json",
        "eval.txt": "eval --scene flicker --methods svgf:alpha=0.1:kernel_size=3,accum,"
                    "svgf:backend=vulkan:illumination=fp16 --sweep --frames 20-45 --size 320x180 --ref-spp 64",
        "bench.txt": "bench --backend cpu,vulkan --size 1920x1080 --runs 3 --warmup 1 --scenes all --submits 2",
        "compare.txt": "compare --in out/a --frames 0-4 --csv out/c.csv --rel-floor 0.01 --max-rel-error 0.5",
        "check.txt": "check --in out/a --method asvgf --frames 0-4",
    }
    for name, line in commands.items():
        write("cli_args_fuzz", name, ("\n".join(line.split()) + "\n").encode("ascii"))


if __name__ == "__main__":
    main()
