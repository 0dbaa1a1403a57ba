#!/usr/bin/env bash
# The installed CMake package, used the way a user's own project uses it (README.md, "Use it from your own
# project"): install the build into a scratch prefix, configure and build examples/shader_port_check against it,
# and run it. Its exact port must match the golden a-trous level to the bit (worst difference 0, exit 0); the
# same port with a deliberate off-by-one tap must be caught (exit 1). The filters component must not bring
# Embree, tinygltf or Vulkan.
# Arguments: the build folder, the source folder, and the build's C++ compiler, flags, generator and make program
# (so that a sanitizer build links its instrumented libraries with the same flags).
set -euo pipefail
build=$1 source=$2 compiler=$3 flags=$4 generator=$5 make_program=$6
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
targets="$work/prefix/lib/cmake/rtdr/rtdrFiltersTargets.cmake"
if grep -n -i -E "embree|tinygltf|vulkan" "$targets"; then
  echo "FAIL: the filters component depends on Embree, tinygltf or Vulkan ($targets)"; exit 1
fi

# Configures, builds and runs the example; prints its output and returns its exit status.
run_example() {  # $1: a name, $2: ON or OFF for PORT_OFF_BY_ONE
  cmake -S "$source/examples/shader_port_check" -B "$work/$1" -G "$generator" -DCMAKE_MAKE_PROGRAM="$make_program" \
    -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_PREFIX_PATH="$work/prefix" \
    -DPORT_OFF_BY_ONE="$2" > "$work/$1.configure.log" || { cat "$work/$1.configure.log"; return 99; }
  cmake --build "$work/$1" > "$work/$1.build.log" || { cat "$work/$1.build.log"; return 99; }
  "$work/$1/shader_port_check"
}

set +e
exact=$(run_example exact OFF); exact_status=$?
off=$(run_example off_by_one ON); off_status=$?
set -e
echo "$exact"
echo "$off"
[ "$exact_status" -eq 0 ] && grep -q "^PASS: worst difference 0$" <<< "$exact" ||
  { echo "FAIL: the exact port did not match the golden pass (exit $exact_status)"; exit 1; }
[ "$off_status" -eq 1 ] && grep -q "^FAIL: worst difference" <<< "$off" ||
  { echo "FAIL: the off-by-one port was not caught (exit $off_status)"; exit 1; }
echo "ok: installed package, exact port matches, off-by-one port caught"
