#!/usr/bin/env bash
# Validates and times the Vulkan ports on a machine with an NVIDIA GPU that has CMake, ninja and a compiler but
# no package registry (the device machine of docs/performance.md). Run tools/gpu_deps.sh first, on Debian 12, and
# take .gl/ and .deps/ along. Usage, from the repository root:
#   bash tools/gpu_device.sh [info] [targets] [trmv] [test] [compare] [bench] [options]   (default: all seven;
#   none: build only)
#     info     the GPU, the Vulkan device, and a device-to-device copy's bandwidth (PyTorch, where there is one)
#     targets  the ports alone at 1920x1080, docs/performance.md's "An NVIDIA H100, again": svgf (fp16 and fp32
#              records) and asvgf on pillars, each frame submitted 100 times and the last timed (with 10 the GPU
#              idles while the host packs the next frame, and never reaches its working clock). Needs only
#              `rtdr`, so it runs before the test programs are built
#     trmv     trmv on fence at 1920x1080 likewise (its cone re-shading takes seconds a frame on the host), then the
#              render side's ports (--stage motion on fence, --stage gradients on pillars), one run each: their
#              CPU columns trace the frame, with TRMV's 64-sample shading term
#     test     a build with RTDR_VULKAN_TESTS_ONLY, then ctest -L vulkan (validation layer on)
#     compare  rtdr compare on 10 frames of pillars at 320x180, every buffer of the ports against the golden
#              passes, with the GPU's default fp16 illumination records and with fp32 records; then asvgf (pillars
#              with gradient samples) and trmv (fence with the shading term) likewise
#     bench    rtdr bench --backend cpu,vulkan on pillars at 1280x720 and 1920x1080 (a GPU's defaults: storage
#              inputs, fp16 illumination records), then the ports alone with fp32 records
#              (RTDR_VK_ILLUMINATION=fp32) and with texel-buffer inputs (RTDR_VK_INPUTS=texel); each frame submitted
#              100 times back to back and the last timed, so that the GPU runs at its working clock (--submits);
#              then asvgf and trmv on their ports at 1920x1080 (docs/performance.md's A-SVGF and TRMV rows), and
#              the render side's ports (--stage gradients, --stage motion) at 1920x1080
#     options  the ports alone at 1920x1080 in the cheaper configurations whose accuracy docs/performance.md
#              measures ("What 0.5 ms would cost"): 4 and 3 a-trous levels, the 3x3 kernel, the 3x3 kernel with 4
#              levels
# The logs, CSVs and the SM clock go to $LOGS (default /tmp/rtdr_device), packed after every step into
# $OUT/device.tgz (default out/device): the device tool brings back 8 files at most, and whatever a step had
# written when a time limit struck. Each step's summary is printed too. The `targets` and `bench` steps' CSVs are
# the experiments gpu-targets and gpu-bench of eval/experiments.toml: back here, with device.tgz unpacked into DIR,
# `tools/reproduce.py --from-csv gpu-targets DIR` writes their tables into docs/performance.md.
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/device}
LOGS=${LOGS:-/tmp/rtdr_device}
mkdir -p "$OUT" "$LOGS"
# Everything in $LOGS, as one archive in $OUT, replaced atomically.
pack() { tar czf "$OUT/device.tgz.part" -C "$LOGS" . && mv "$OUT/device.tgz.part" "$OUT/device.tgz"; }
steps=("$@")
((${#steps[@]})) || steps=(info targets trmv test compare bench options)
[ "${steps[*]}" = build ] && steps=()
wants() { [[ " ${steps[*]} " == *" $1 "* ]]; }

# The loaders go into / (they are what a GPU machine's driver expects to find); everything else into a prefix.
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
DEPS=/tmp/deps
rm -rf "$DEPS"
# libvulkan1 also into the prefix: libvulkan-dev's libvulkan.so links to it there.
for f in .deps/*.deb .gl/libvulkan1_*.deb; do dpkg -x "$f" "$DEPS"; done
export PATH="$DEPS/usr/bin:$PATH"
export LD_LIBRARY_PATH="$DEPS/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export VK_LAYER_PATH="$DEPS/usr/share/vulkan/explicit_layer.d"
# The NVIDIA driver's manifest, where the image keeps it outside the loader's search path.
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f "$icd" ] && ! ls /usr/share/vulkan/icd.d/nvidia_icd.json /etc/vulkan/icd.d/nvidia_icd.json >/dev/null 2>&1; then
  export VK_DRIVER_FILES="$icd" VK_ICD_FILENAMES="$icd"
fi

# For commands run after this script on the same machine: `source /tmp/deps/env.sh`.
declare -p PATH LD_LIBRARY_PATH VK_LAYER_PATH >"$DEPS/env.sh"
declare -p VK_DRIVER_FILES VK_ICD_FILENAMES >>"$DEPS/env.sh" 2>/dev/null

if wants info; then
  nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv 2>&1 |
    tee "$LOGS/info.txt"
  python3 - <<'EOF' 2>&1 | tee -a "$LOGS/info.txt"
# A device-to-device copy of 1 GiB: the memory bandwidth the passes' bytes are set against.
try:
    import torch
except ImportError:
    raise SystemExit("no PyTorch: copy bandwidth not measured")
a = torch.empty(1 << 28, dtype=torch.float32, device="cuda").normal_()
b = torch.empty_like(a)
for _ in range(3):
    b.copy_(a)
start, stop = torch.cuda.Event(enable_timing=True), torch.cuda.Event(enable_timing=True)
times = []
for _ in range(20):
    start.record(); b.copy_(a); stop.record(); stop.synchronize()
    times.append(start.elapsed_time(stop))
ms = sorted(times)[len(times) // 2]
print(f"device-to-device copy of 1 GiB: {ms:.3f} ms median, {2 * a.numel() * 4 / (ms * 1e-3) / 1e9:.0f} GB/s read + written")
EOF
  pack
fi

BUILD=build-gpu
# `rtdr` first, so that the timings need not wait for the test programs; those are built only for `test`.
build() {
  cmake --build "$BUILD" -j "$(nproc)" "$@" >>"$LOGS/build.log" 2>&1 || { tail -40 "$LOGS/build.log"; pack; exit 1; }
}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$DEPS/usr" \
  -DRTDR_VULKAN_TESTS_ONLY=ON -DRTDR_VIEW=OFF >"$LOGS/build.log" 2>&1 || { tail -40 "$LOGS/build.log"; pack; exit 1; }
build --target rtdr
echo "built: $BUILD/app/rtdr"

status=0
clocks=
# The SM clock while anything is timed (the card as found: its settings are never changed).
if wants targets || wants trmv || wants bench || wants options; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,utilization.gpu --format=csv -lms 250 \
    >"$LOGS/clocks.csv" 2>&1 &
  clocks=$!
fi

rtdr_bench() { "$BUILD/app/rtdr" bench --size 1920x1080 "$@" 2>&1 | tee -a "$LOGS/targets.txt" || status=1; }
if wants targets; then
  # The whole filter on its ports: svgf as a GPU runs it (fp16 records), then with fp32 records; asvgf.
  rtdr_bench --backend vulkan --scenes pillars --runs 5 --warmup 5 --submits 100 --csv "$LOGS/targets_svgf.csv"
  RTDR_VK_ILLUMINATION=fp32 rtdr_bench --backend vulkan --scenes pillars --runs 5 --warmup 5 --submits 100 \
    --csv "$LOGS/targets_svgf_fp32.csv"
  rtdr_bench --backend vulkan --method asvgf --scenes pillars --runs 5 --warmup 5 --submits 100 \
    --csv "$LOGS/targets_asvgf.csv"
  pack
fi

if wants trmv; then
  rtdr_bench --backend vulkan --method trmv --scenes fence --runs 3 --warmup 5 --submits 100 \
    --csv "$LOGS/targets_trmv.csv"
  pack
  rtdr_bench --stage motion --backend vulkan --scenes fence --runs 1 --warmup 0 --csv "$LOGS/targets_motion.csv"
  rtdr_bench --stage gradients --backend vulkan --scenes pillars --runs 1 --warmup 0 \
    --csv "$LOGS/targets_gradients.csv"
  pack
fi

if wants test; then
  build
  ctest --test-dir "$BUILD" -L vulkan --output-on-failure -j 4 >"$LOGS/ctest.log" 2>&1 || status=1
  grep -E "tests passed|tests failed|Failed|\*\*\*" "$LOGS/ctest.log" | head -30
  pack
fi

if wants compare; then
  # The rendered frames stay outside $LOGS, which comes back from the machine packed.
  frames=/tmp/rtdr_compare_in
  "$BUILD/app/rtdr" render --scene pillars --frames 0-9 --size 320x180 --out "$frames" >/dev/null || status=1
  for records in fp16 fp32; do
    RTDR_VK_ILLUMINATION=$records "$BUILD/app/rtdr" compare --in "$frames" --csv "$LOGS/compare_$records.csv" \
      >"$LOGS/compare_$records.txt" 2>&1 || status=1
    grep -E "^(svgf|color|display)" "$LOGS/compare_$records.txt"
  done
  "$BUILD/app/rtdr" render --scene pillars --frames 0-9 --size 320x180 --gradients --out "$frames-asvgf" \
    >/dev/null || status=1
  "$BUILD/app/rtdr" render --scene fence --frames 0-9 --size 320x180 --shading-samples 64 --out "$frames-trmv" \
    >/dev/null || status=1
  for method in asvgf trmv; do
    "$BUILD/app/rtdr" compare --method $method --in "$frames-$method" --csv "$LOGS/compare_$method.csv" \
      >"$LOGS/compare_$method.txt" 2>&1 || status=1
    grep -E "^($method|color|display)" "$LOGS/compare_$method.txt"
  done
  pack
fi

if wants bench; then
  for size in 1280x720 1920x1080; do
    # The ports as a GPU runs them against the golden passes, then the fp32 records, then the texel-buffer build.
    "$BUILD/app/rtdr" bench --backend cpu,vulkan --scenes pillars --size "$size" --runs 20 --warmup 5 \
      --submits 100 --csv "$LOGS/bench_$size.csv" 2>&1 | tee -a "$LOGS/bench.txt" || status=1
    for variant in RTDR_VK_ILLUMINATION=fp32 RTDR_VK_INPUTS=texel; do
      echo "$variant:" | tee -a "$LOGS/bench.txt"
      env "$variant" "$BUILD/app/rtdr" bench --backend vulkan --scenes pillars --size "$size" --runs 20 \
        --warmup 5 --submits 100 --csv "$LOGS/bench_${variant#*=}_$size.csv" 2>&1 | tee -a "$LOGS/bench.txt" || status=1
    done
  done
  # A-SVGF's whole frame and TRMV's filter on the ports (the golden passes would take minutes at 1080p).
  for method_scene in asvgf:pillars trmv:fence; do
    "$BUILD/app/rtdr" bench --backend vulkan --method "${method_scene%%:*}" --scenes "${method_scene#*:}" \
      --size 1920x1080 --runs 20 --warmup 5 --submits 100 --csv "$LOGS/bench_${method_scene%%:*}.csv" 2>&1 |
      tee -a "$LOGS/bench.txt" || status=1
  done
  for stage in gradients motion; do
    "$BUILD/app/rtdr" bench --stage $stage --backend cpu,vulkan --scenes pillars,fence --size 1920x1080 --runs 5 \
      --warmup 1 --csv "$LOGS/bench_$stage.csv" 2>&1 | tee -a "$LOGS/bench.txt" || status=1
  done
  pack
fi

if wants options; then
  # The configurations a 0.5 ms target could take (docs/performance.md), each timed like the bench step.
  for params in "--atrous-levels 4" "--atrous-levels 3" "--kernel-size 3" "--kernel-size 3 --atrous-levels 4"; do
    # shellcheck disable=SC2086  # $params is two or four words on purpose
    "$BUILD/app/rtdr" bench --backend vulkan --scenes pillars --size 1920x1080 --runs 20 --warmup 5 --submits 100 \
      $params --csv "$LOGS/options_${params//[ -]/}.csv" 2>&1 | tee -a "$LOGS/options.txt" || status=1
  done
  pack
fi
[ -n "$clocks" ] && kill "$clocks" && pack
exit $status
