#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ (fuzz/README.md) with clang into build-fuzz/ and runs each one.
# Exits non-zero when any harness finds something: a crash, a sanitizer report, a timeout, an out-of-memory,
# or an exception that is not rtdr::Error.
#
#   bash tools/fuzz.sh [SECONDS]    explore: each harness for SECONDS seconds (default 60), a new seed each time
#   bash tools/fuzz.sh --runs=N     replay: each harness for N inputs from seed 1 and the seeds in git (CI)
#
# Exploring finds new inputs but never the same ones twice, so it cannot gate a merge: a run that passes
# here could fail in CI on the same code. A replay fixes the seed and the number of inputs, so two machines
# try nearly the same inputs on the same code. Not exactly: an input's coverage can depend on the state the
# libraries keep between inputs, and libFuzzer steers by coverage (two replays here reached 799 and 788
# coverage points in exr_reader_fuzz, and the same 1571 in gltf_loader_fuzz).
#
# Exploring works on build-fuzz/corpus/<harness>/, which starts as a copy of fuzz/corpus/<harness>/ and
# keeps what earlier runs found (delete it to start over); a replay starts from a fresh copy every time. The
# seeds in git are never written to. Inputs that fail are saved in build-fuzz/findings/<harness>/, each
# run's output in build-fuzz/logs/<harness>.log.
set -euo pipefail
cd "$(dirname "$0")/.."

budget=(-max_total_time="${1:-60}")
what="for ${1:-60} s"
if [[ "${1:-}" =~ ^--runs=([1-9][0-9]*)$ ]]; then
  budget=(-runs="${BASH_REMATCH[1]}" -seed=1)
  what="for ${BASH_REMATCH[1]} inputs from seed 1"
  replay=1
elif ! [[ "${1:-60}" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: bash tools/fuzz.sh [SECONDS | --runs=N]" >&2
  exit 2
fi

# The project's own dependencies (and build/: an up-to-date check once it is built), then clang with its
# runtime libraries (compiler-rt: libFuzzer, AddressSanitizer, UndefinedBehaviorSanitizer), which Debian
# packages separately from the compiler.
bash tools/setup.sh
PACKAGES=(clang libclang-rt-dev)
bash tools/install_missing.sh fuzz "${PACKAGES[@]}"

# Only the harnesses and the libraries they link; no tests (RTDR_FUZZ in CMakeLists.txt says what is
# instrumented). RelWithDebInfo: -O2 for speed, -g for the stack traces in a report.
[ -f build-fuzz/build.ninja ] ||
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRTDR_FUZZ=ON \
    -DRTDR_BUILD_TESTS=OFF
cmake --build build-fuzz --target rtdr_fuzz

# Sanitizer reports with stack traces; UBSan stops at the first report (also set at compile time). ASan records
# 3 frames of each allocation's stack instead of 30: cli_args_fuzz builds rtdr's whole command line per input, some
# thousands of allocations, and recording their stacks took a third of its time (30 inputs a second, 646 s for
# CI's 20000, on 2026-11-27). A report's own stack is whole; a finding's saved input replays with full stacks.
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1:malloc_context_size=3}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

summary=()
failed=0
for harness in gltf_loader_fuzz exr_reader_fuzz cli_args_fuzz; do
  corpus="build-fuzz/corpus/$harness" findings="build-fuzz/findings/$harness" log="build-fuzz/logs/$harness.log"
  # A replay starts from the seeds in git alone, never from what earlier runs on this machine kept.
  [ -z "${replay:-}" ] || { corpus="build-fuzz/replay/$harness"; rm -rf "$corpus"; }
  mkdir -p "$corpus" "$findings" build-fuzz/logs
  cp fuzz/corpus/"$harness"/* "$corpus"/
  echo "fuzz: $harness $what (log: $log)"
  # -timeout: one input taking 10 s is a hang. -rss_limit_mb: more memory than this is a finding too.
  status=0
  "build-fuzz/fuzz/$harness" "$corpus" -dict="fuzz/$harness.dict" "${budget[@]}" -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 </dev/null >"$log" 2>&1 || status=$?

  # libFuzzer's last lines: "Done N runs in S second(s)", and the last status line "#N ... cov: C ft: F".
  runs=$(sed -n 's/^Done \([0-9]*\) runs in \([0-9]*\) second.*/\1 runs in \2 s/p' "$log" | tail -1)
  coverage=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 || true)
  if ((status == 0)); then
    files=$(find "$corpus" -type f | wc -l)
    summary+=("fuzz: $harness: ${runs:-? runs}, ${coverage:-no coverage line}, $files corpus files: nothing found")
  else
    failed=1
    found="fuzz: $harness: FOUND SOMETHING (exit $status) after ${runs:-an unknown number of runs}"
    summary+=("$found; input(s) in $findings/, log $log")
    echo "----- the end of $log -----"
    tail -n 60 "$log"
    echo "----- reproduce: build-fuzz/fuzz/$harness $findings/<file> -----"
  fi
done

printf '%s\n' "${summary[@]}"
exit "$failed"
