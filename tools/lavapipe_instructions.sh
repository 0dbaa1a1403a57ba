#!/bin/bash
# Counts the instructions the Vulkan ports execute on lavapipe: `rtdr bench --backend vulkan` on pillars at a small
# size under valgrind's callgrind, summed over the shaders' JIT code (callgrind lists it as `???` entries, one per
# compiled shader, largest first). Unlike wall time on a shared machine, which moves by tens of percent from run to
# run, the count is the same every run, so it shows what a change to a shader buys (docs/performance.md).
#
#   bash tools/lavapipe_instructions.sh [WxH] [frames]   (defaults 320x180, 4: 1 warm-up + 3 timed)
#
# Needs valgrind (apt-get install valgrind) and a build in build/ (bash tools/test.sh makes one). Takes about two
# minutes at the defaults.
set -euo pipefail
cd "$(dirname "$0")/.."

size=${1:-320x180}
frames=${2:-4}
if ! command -v valgrind >/dev/null; then
  echo "lavapipe_instructions.sh: valgrind is not installed (apt-get install valgrind)" >&2
  exit 1
fi
if [ ! -x build/app/rtdr ]; then
  echo "lavapipe_instructions.sh: no build/app/rtdr; build first (bash tools/test.sh)" >&2
  exit 1
fi

mkdir -p out
profile=out/lavapipe_callgrind.out
RTDR_VK_INPUTS=${RTDR_VK_INPUTS:-texel} valgrind --tool=callgrind --callgrind-out-file="$profile" \
  build/app/rtdr bench --stage filter --method svgf --size "$size" --scenes pillars --backend vulkan \
  --runs $((frames - 1)) --warmup 1 >/dev/null 2>&1
callgrind_annotate --threshold=100 "$profile" 2>/dev/null | grep '\[???\]' | tr -d ',' |
  awk -v size="$size" -v frames="$frames" '
    { total += $1; if (NR <= 8) top[NR] = $1 }
    END {
      printf "lavapipe, pillars %s, %d frames: %.1f M instructions in the shaders\n", size, frames, total / 1e6
      printf "largest compiled shaders (M):"
      for (i = 1; i <= 8 && i in top; ++i) printf " %.1f", top[i] / 1e6
      printf "\n"
    }'
