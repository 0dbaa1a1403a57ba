#!/usr/bin/env bash
# The main job: set up, build, then evaluate the methods against reference frames. Writes to out/demo/:
#   frames/                the 1-spp pillars frames (every G-buffer and radiance layer) with PNG previews
#   metrics.csv            every method and the SVGF sweeps on pillars (eleven pillars moving in front of an
#                          area light), per frame, against 128-spp references
#   speed_vs_accuracy.png  mean time per frame against mean error, Pareto front marked
#   error_over_frames.png  error per frame and method
#   strip.png              the last frame: 1-spp input | svgf | accum | eaw | eaw-accum | none | reference
#   static/                the same on the still scene; static/temporal_error.png is SVGF Fig. 10's chart
#   fence/                 TRMV's Fig. 8: the fence's moving shadows, trmv along the shadow motion and along the
#                          surface motion beside svgf and asvgf (filters/trmv/README.md)
# References are cached in out/cache/, so a second run takes seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
build/app/rtdr render --scene pillars --frames 0-23 --size 320x180 --out out/demo/frames
build/app/rtdr eval --scene pillars --methods all --sweep --frames 0-23 --size 320x180 --ref-spp 128 \
  --cache out/cache --out out/demo
build/app/rtdr eval --scene static --methods svgf,asvgf,accum,eaw,none --frames 0-23 --size 320x180 --ref-spp 16 \
  --cache out/cache --out out/demo/static
build/app/rtdr eval --scene fence --methods svgf,asvgf,trmv,trmv:motion=traditional --frames 0-15 --size 320x180 \
  --ref-spp 64 --cache out/cache --out out/demo/fence
