#!/usr/bin/env bash
# The main job: set up, build, and render the default scene's G-buffer sequence into out/demo/
# (one multi-layer EXR per frame, a PNG preview beside each).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
build/app/rtdr render --scene pillars --frames 0-23 --size 640x360 --out out/demo
