#!/bin/bash
# Renders a glTF scene with RTDR and with Blender's Cycles and compares them: prints the mean RGB ratio
# RTDR / Cycles and a map of per-block luminance ratios, for each Cycles material asked for. A tool for users,
# run by hand; not part of the test suite (Blender: `apt-get install -y --no-install-recommends blender`,
# Debian 12 has 3.4). Settings that match RTDR: tools/compare_cycles_blender.py; what differs: trace/README.md.
#
#   tools/compare_cycles.sh SCENE.gltf [--size WxH] [--spp N] [--max-bounces B] [--blocks K] [--out DIR]
#                                      [--cycles-material principled|lambert|both]
#
# --cycles-material (default both): `principled` renders the importer's Principled BSDF, what Blender 3.4 shows;
# `lambert` a Diffuse BSDF (Lambert, glTF's diffuse lobe) plus emission in its place, glTF's BRDF but for its
# specular lobe. Defaults: 128x128, 256 spp, 1 bounce, 4 x 4 blocks, out/compare_cycles. Both renderers get the
# same size, samples and bounces; RTDR frame 0 (t = 0). Needs build/app/rtdr (cmake --build build), blender,
# and /usr/bin/python3 with numpy and OpenImageIO (Debian's python3-numpy, python3-openimageio).
set -euo pipefail

usage() { sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[[ $# -ge 1 ]] || usage
scene=$1; shift
size=128x128 spp=256 bounces=1 blocks=4 out=out/compare_cycles materials=both
while [[ $# -gt 0 ]]; do
  case $1 in
    --size) size=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --max-bounces) bounces=$2; shift 2 ;;
    --blocks) blocks=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --cycles-material) materials=$2; shift 2 ;;
    *) usage ;;
  esac
done
case $materials in
  principled|lambert) ;;
  both) materials="principled lambert" ;;
  *) usage ;;
esac
root=$(cd "$(dirname "$0")/.." && pwd)
[[ -f $scene ]] || { echo "compare_cycles: no such file: $scene" >&2; exit 1; }
scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")
width=${size%x*} height=${size#*x}
mkdir -p "$out"
out=$(cd "$out" && pwd)

echo "RTDR: $size, $spp spp, $bounces bounce(s)"
"$root/build/app/rtdr" render --scene "$scene" --frames 0 --size "$size" --spp "$spp" --max-bounces "$bounces" \
  --out "$out/rtdr" | tail -1
reports=()
for material in $materials; do
  echo "Cycles ($material): $size, $spp spp, $bounces bounce(s)"
  rm -f "$out/cycles_$material.exr"
  blender -b --factory-startup -P "$root/tools/compare_cycles_blender.py" -- \
    "$scene" "$out/cycles_$material.exr" "$width" "$height" "$spp" "$bounces" "$material" 2>&1 |
    grep -E "^compare_cycles|Saved|Error" || true
  [[ -f $out/cycles_$material.exr ]] || { echo "compare_cycles: Blender wrote no image" >&2; exit 1; }
  reports+=("$material=$out/cycles_$material.exr")
done
/usr/bin/python3 "$root/tools/compare_cycles_report.py" "$out/rtdr/frame_0000.exr" "$blocks" "${reports[@]}"
