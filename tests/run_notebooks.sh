#!/usr/bin/env bash
# Executes the classroom notebooks headless on a tiny sequence, as a person would run them (ctest label
# `notebooks`). Usage: tests/run_notebooks.sh path/to/rtdr path/to/source. Fails when any cell raises.
set -euo pipefail
rtdr=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$rtdr" render --scene pillars --frames 0-5 --size 64x36 --out "$work/in" > /dev/null
"$rtdr" filter --method svgf --in "$work/in" --out "$work/svgf" --dump-passes > /dev/null
# asvgf_walkthrough: 8 frames with gradient samples, filtered by both methods, and 4-spp reference frames.
"$rtdr" render --scene pillars --frames 0-7 --size 128x72 --gradients --out "$work/gradients" > /dev/null
"$rtdr" filter --method asvgf --in "$work/gradients" --out "$work/asvgf" --dump-passes > /dev/null
"$rtdr" filter --method svgf --in "$work/gradients" --out "$work/gradients-svgf" --dump-passes > /dev/null
"$rtdr" render --scene pillars --frames 0-7 --size 128x72 --spp 4 --out "$work/reference" > /dev/null 2>&1
# trmv_walkthrough: one frame and the one before of fence, glossy and occlusion, and glossy's again with another seed.
"$rtdr" render --scene fence --frames 7-8 --size 160x90 --shading-samples 4 --out "$work/trmv-fence" > /dev/null
"$rtdr" filter --method trmv --in "$work/trmv-fence" --out "$work/trmv-fence-trmv" --dump-passes > /dev/null
"$rtdr" render --scene glossy --frames 19-20 --size 160x90 --out "$work/trmv-glossy" > /dev/null
"$rtdr" render --scene glossy --frames 20 --size 160x90 --seed 1 --out "$work/trmv-glossy-reseed" > /dev/null
"$rtdr" render --scene occlusion --frames 39-40 --size 160x90 --out "$work/trmv-occlusion" > /dev/null
"$rtdr" eval --scene pillars --methods svgf,accum,eaw,none --sweep --frames 0-3 --size 64x36 --ref-spp 8 \
  --cache "" --out "$work/eval" > /dev/null 2>&1

export RTDR_WALKTHROUGH_IN="$work/in" RTDR_WALKTHROUGH_DUMP="$work/svgf" RTDR_EXE="$rtdr"
export RTDR_ASVGF_IN="$work/gradients" RTDR_ASVGF_DUMP="$work/asvgf" RTDR_ASVGF_SVGF_DUMP="$work/gradients-svgf"
export RTDR_ASVGF_REF="$work/reference"
export RTDR_TRMV_FENCE="$work/trmv-fence" RTDR_TRMV_FENCE_DUMP="$work/trmv-fence-trmv" RTDR_TRMV_GLOSSY="$work/trmv-glossy"
export RTDR_TRMV_GLOSSY_RESEED="$work/trmv-glossy-reseed" RTDR_TRMV_OCCLUSION="$work/trmv-occlusion"
export RTDR_METRICS="$work/eval/metrics.csv" MPLBACKEND=Agg PYDEVD_DISABLE_FILE_VALIDATION=1
for notebook in svgf_walkthrough speed_vs_accuracy asvgf_walkthrough trmv_walkthrough; do
  # Debian's nbconvert and its python3 kernel (/usr/bin/python3, with numpy, matplotlib and OpenImageIO).
  /usr/bin/jupyter-nbconvert --to notebook --execute "$src/notebooks/$notebook.ipynb" --output-dir "$work" \
    --ExecutePreprocessor.kernel_name=python3 --ExecutePreprocessor.timeout=120 --log-level=WARN
  echo "executed $notebook.ipynb"
done
