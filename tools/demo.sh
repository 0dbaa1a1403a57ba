#!/usr/bin/env bash
# The demo: each paper's point, on the scene that shows it, against path-traced references. Sets up, builds only the
# `rtdr` command, then writes to out/demo/ (README.md, "Quick start", says what each picture shows):
#   frames/       the 1-spp pillars frames 0-9 at 320x180 (every G-buffer and radiance layer, PNG previews): an
#                 input for `rtdr filter` and `rtdr probe`; rendered once
#   pillars/      SVGF [SVGF17] against temporal accumulation alone (accum), the a-trous filter alone (eaw) and the
#                 unfiltered input (none): frames 0-9 of the moving pillars, 128-spp references
#   flicker/      A-SVGF [ASVGF18] against SVGF where lambda matters: a light switching on at frame 30, frames 26-35,
#                 64-spp references
#   shadow-fold/  TRMV [TRMV21] along its own vectors against TRMV along the traditional (surface) vector: a moving
#                 light's shadow sliding over a static floor and a fold, frames 26-35, 64-spp references
# Each of the three holds metrics.csv, speed_vs_accuracy.png, error_over_frames.png, temporal_error.png and
# strip.png. References and inputs are cached in out/cache/: a rerun filters and evaluates again, and renders
# nothing.
#
# bash tools/demo.sh --full: the full sweep instead, into out/demo/full/: every method and the parameter sweeps on
# 24 frames of pillars, A-SVGF's baselines over the flicker's switches (frames 20-45), every TRMV motion beside SVGF
# and A-SVGF on the fence of TRMV's Fig. 8 (frames 0-23), and static/ (SVGF Fig. 10's temporal stability on a still
# scene, against 256-spp references).
set -euo pipefail
cd "$(dirname "$0")/.."
full=0
case "${1:-}" in
  "") ;;
  --full) full=1 ;;
  *) echo "usage: bash tools/demo.sh [--full]" >&2; exit 2 ;;
esac
bash tools/setup.sh rtdr
rtdr=build/app/rtdr
start=$SECONDS
step() { printf '\n== %s (%d s so far)\n' "$1" $((SECONDS - start)); }
eval_run() { "$rtdr" eval --size 320x180 --cache out/cache "$@"; }

if ((full == 0)); then
  if [ ! -f out/demo/frames/frame_0009.exr ]; then
    step "frames: 10 one-sample frames of pillars"
    "$rtdr" render --scene pillars --frames 0-9 --size 320x180 --out out/demo/frames
  fi
  step "pillars: SVGF against temporal accumulation alone, the a-trous filter alone and the input"
  eval_run --scene pillars --methods svgf,accum,eaw,none --frames 0-9 --ref-spp 128 --out out/demo/pillars
  step "flicker: A-SVGF against SVGF, a light switching on at frame 30"
  eval_run --scene flicker --methods svgf,asvgf --frames 26-35 --ref-spp 64 --out out/demo/flicker
  step "shadow-fold: TRMV along its own vectors against TRMV along the surface motion"
  eval_run --scene shadow-fold --methods trmv,trmv:motion=traditional --frames 26-35 --ref-spp 64 \
    --out out/demo/shadow-fold
else
  step "frames: 24 one-sample frames of pillars"
  "$rtdr" render --scene pillars --frames 0-23 --size 320x180 --out out/demo/full/frames
  step "pillars: every method and the parameter sweeps"
  eval_run --scene pillars --methods all --sweep --frames 0-23 --ref-spp 128 --out out/demo/full/pillars
  step "flicker: A-SVGF and its baselines over the light's switches"
  eval_run --scene flicker --methods svgf,asvgf,eaw,a-eaw --frames 20-45 --ref-spp 128 --out out/demo/full/flicker
  step "fence: every TRMV motion beside SVGF and A-SVGF"
  eval_run --scene fence --frames 0-23 --ref-spp 128 --out out/demo/full/fence \
    --methods svgf,asvgf,trmv,trmv:motion=traditional,trmv:motion=shadow,trmv:motion=dual,trmv:motion=glossy
  step "static: temporal stability on a still scene"
  eval_run --scene static --methods svgf,asvgf,accum,eaw,none --frames 0-23 --ref-spp 256 --out out/demo/full/static
fi
printf '\ndemo: %d s after the build; pictures in out/demo/%s\n' $((SECONDS - start)) "$( ((full)) && echo full/)"
if ((full == 0)); then
  printf 'every pass of SVGF on the demo frames, in the browser (docs/view.md):\n  %s view --in out/demo/frames --method svgf\n' \
    "$rtdr"
fi
