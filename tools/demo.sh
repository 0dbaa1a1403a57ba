#!/usr/bin/env bash
# The main job: set up, build, then evaluate every method on the default scene (pillars: eleven pillars
# moving in front of an area light) against reference frames. Writes to out/demo/: metrics.csv, the three
# charts (speed_vs_accuracy.png, error_over_frames.png, temporal_error.png) and strip.png (the last frame:
# 1-spp input, each method, the reference), plus the rendered input frames with their previews in
# out/demo/frames/. References are cached in out/cache/, so a second run takes seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
build/app/rtdr render --scene pillars --frames 0-23 --size 320x180 --out out/demo/frames
build/app/rtdr eval --scene pillars --methods all --sweep --frames 0-23 --size 320x180 --ref-spp 128 \
  --cache out/cache --out out/demo
