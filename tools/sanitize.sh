#!/usr/bin/env bash
# The test suite under AddressSanitizer and UndefinedBehaviorSanitizer: configures and builds build-asan/, then
# runs every test except those labelled vulkan (the ports, validated by tools/gpu_device.sh), notebooks
# (the classroom notebooks, Python) and stability (the papers' claims on long sequences: the code they run, the
# unit tests run on small frames; docs/reliability.md "Sanitizers"). The first report stops the process that made it and fails its test.
# Run tools/setup.sh first: it installs the packages. Usage, from anywhere: bash tools/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# Debug leaves assert() on. -O1, not Debug's -O0, for speed; -O2 took half as long again to build and ran
# the tests no faster (measured on 2 cores). -fno-sanitize-recover=all makes UBSan stop at its first report,
# as ASan does. GCC's -Wmaybe-uninitialized gives false warnings under ASan (in <regex>, here): off here only.
# The tests labelled vulkan and stability are not built (RTDR_VULKAN_TESTS=OFF, RTDR_STABILITY_TESTS=OFF); rtdr
# and its Vulkan back end are.
SANITIZE="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -Wno-maybe-uninitialized"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="$SANITIZE" \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DRTDR_VULKAN_TESTS=OFF -DRTDR_STABILITY_TESTS=OFF
cmake --build build-asan

# The tests that run `rtdr` run the sanitized one of this build (RTDR_EXE), which inherits these options; a
# report in its stderr fails the test (tests/cli_fixtures.h). detect_leaks=1 is ASan's default, written out.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1"
# lavapipe, the CPU Vulkan driver the tests run the ports on, allocates 128 bytes when an instance is made, and the
# Vulkan loader unloads it at vkDestroyInstance with them still allocated: LeakSanitizer then reports a direct leak
# "from <unknown module>" in every process that used Vulkan (mesa 22.3.6-1+deb12u2, Debian 12; a five-line program
# that makes and destroys an instance shows it). Preloaded, the driver stays loaded, its memory stays reachable and
# is not a leak; a leak of ours is still reported. The driver comes before the sanitizer runtime in the library list
# then, which ASan accepts with verify_asan_link_order=0.
lavapipe=$(ls /usr/lib/*/libvulkan_lvp.so 2>/dev/null | head -n 1 || true)
if [ -n "$lavapipe" ]; then
  export LD_PRELOAD="$lavapipe"
  ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
fi
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE 'vulkan|notebooks|stability'
