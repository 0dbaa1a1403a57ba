#!/usr/bin/python3
"""The behaviour of an rtdr build, as one line per output channel: a fingerprint to compare before and after a
change that must not change any output (a refactoring, a move of code between folders).

    /usr/bin/python3 tools/fingerprint.py RTDR OUT > fingerprint.txt

RTDR is the rtdr binary, OUT a scratch folder (emptied). Every shipped scene is rendered (3 frames at 40x24: plain,
with A-SVGF's gradient samples, and with TRMV's shading term), then filtered by every method on the input it reads,
on the CPU and, for the methods with ports, on the Vulkan back end, with --dump-passes, so every intermediate
layer counts. Each line is "<file> <channel> <sha256 of its values>", sorted; the EXR headers are left out (a
build records itself there). Two builds behave the same when their fingerprints are equal:

    diff <(python3 tools/fingerprint.py old/rtdr /tmp/a) <(python3 tools/fingerprint.py new/rtdr /tmp/b)
"""
import hashlib
import os
import shutil
import subprocess
import sys

import OpenImageIO as oiio

SCENES = ["cornell", "falling-light", "fence", "flicker", "glossy", "occlusion", "pillars", "shadow-fold", "static"]
SIZE = "40x24"
FRAMES = "0-2"
# The inputs, by the flags that make them, and the methods that read each, with their back ends.
INPUTS = {
    "plain": ([], {"svgf": ["cpu", "vulkan"], "accum": ["cpu"], "eaw": ["cpu"], "eaw-accum": ["cpu"],
                   "none": ["cpu"]}),
    "gradients": (["--gradients"], {"asvgf": ["cpu", "vulkan"], "a-eaw": ["cpu"]}),
    "shading": (["--shading-samples", "8"], {"trmv": ["cpu", "vulkan"]}),
}


def run(args):
    done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit("fingerprint: %s failed: %s" % (" ".join(args), done.stderr.strip().splitlines()[-1:]))


def channel_hashes(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit("fingerprint: cannot read %s: %s" % (path, oiio.geterror()))
    spec = image.spec()
    # As doubles: exact for the float channels and for every 32-bit id.
    pixels = image.read_image(oiio.DOUBLE)
    image.close()
    for c, name in enumerate(spec.channelnames):
        yield name, hashlib.sha256(pixels[:, :, c].tobytes()).hexdigest()


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rtdr, out = os.path.abspath(sys.argv[1]), sys.argv[2]
    shutil.rmtree(out, ignore_errors=True)
    for scene in SCENES:
        for kind, (flags, methods) in INPUTS.items():
            frames = os.path.join(out, scene, kind)
            run([rtdr, "render", "--scene", scene, "--frames", FRAMES, "--size", SIZE, "--out", frames] + flags)
            for method, backends in methods.items():
                for backend in backends:
                    run([rtdr, "filter", "--method", method, "--backend", backend, "--in", frames, "--dump-passes",
                         "--out", os.path.join(out, scene, kind + "-" + method + "-" + backend)])
    lines = []
    for folder, _, files in os.walk(out):
        for name in files:
            if name.endswith(".exr"):
                path = os.path.join(folder, name)
                for channel, digest in channel_hashes(path):
                    lines.append("%s %s %s" % (os.path.relpath(path, out), channel, digest))
    print("\n".join(sorted(lines)))


if __name__ == "__main__":
    main()
