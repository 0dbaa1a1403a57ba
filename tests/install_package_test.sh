#!/usr/bin/env bash
# The installed RTDR standing alone (README.md, "Use it from your own project"; cmake/install.cmake): installed
# into a scratch prefix, then, with the source tree and every build folder gone, from the prefix alone:
#   1. rtdr render --scene cornell finds the shipped scene in <prefix>/share/rtdr/scenes;
#   2. rtdr eval writes its charts with the scripts of <prefix>/share/rtdr/eval;
#   3. rtdr filter --backend vulkan loads the SPIR-V of <prefix>/share/rtdr/shaders (where a Vulkan device exists);
#   4. the example project installed in <prefix>/share/doc/rtdr/examples builds against the package: its exact port
#      matches the golden a-trous level to the bit (worst difference 0, exit 0), the same port with a deliberate
#      off-by-one tap is caught (exit 1);
#   5. the filters component brings no OpenEXR (nor Imath, whose Debian package prints a note about a missing Python
#      binding), no Embree, tinygltf or Vulkan: neither its exported targets nor the example's configure output
#      name them.
# "Gone", one of two ways. Where a mount namespace can be made (unshare: root, or unprivileged user namespaces),
# this build is installed and the checks run with an empty folder mounted over the source tree and over the build
# folder, so that nothing compiled into rtdr can reach them. Elsewhere, a copy of the source tree is configured,
# built (rtdr and what it links) and installed, then the copy and its build folder are deleted: the same proof,
# at the cost of building rtdr again.
# Arguments: the build folder, the source folder, and the build's C++ compiler, flags, generator, make program and
# compiler launcher ("" for none), so that a sanitizer build links its instrumented libraries with the same flags.
set -euo pipefail
fail() { echo "FAIL: $*"; exit 1; }

# The checks, from the prefix alone. Arguments: the prefix, a scratch folder, compiler, flags, generator, make.
checks() {
  local prefix=$1 work=$2 compiler=$3 flags=$4 generator=$5 make_program=$6
  local rtdr="$prefix/bin/rtdr"
  [ -x "$rtdr" ] || fail "no $rtdr"
  for installed in share/rtdr/scenes/cornell.gltf share/rtdr/eval/charts.py share/rtdr/shaders/atrous.spv \
    share/rtdr/view/index.html share/doc/rtdr/buffers.md share/doc/rtdr/examples/shader_port_check/CMakeLists.txt; do
    [ -f "$prefix/$installed" ] || fail "$installed is not installed"
  done
  cd "$work"  # nothing is read from the working folder either

  # 1. A shipped scene, by name.
  "$rtdr" render --scene cornell --frames 0-1 --size 24x14 --out "$work/cornell" > "$work/render.log" 2>&1 ||
    { cat "$work/render.log"; fail "rtdr render --scene cornell from the prefix"; }
  [ -f "$work/cornell/frame_0001.exr" ] || fail "rtdr render wrote no frame_0001.exr"

  # 2. The charts.
  "$rtdr" eval --scene cornell --methods svgf,none --frames 0-2 --size 24x14 --ref-spp 2 --cache "" \
    --out "$work/eval" > "$work/eval.log" 2>&1 || { cat "$work/eval.log"; fail "rtdr eval from the prefix"; }
  for png in speed_vs_accuracy.png error_over_frames.png temporal_error.png strip.png; do
    [ -s "$work/eval/$png" ] || fail "rtdr eval wrote no $png"
  done

  # 3. The shader ports, where a Vulkan device exists (lavapipe counts).
  if "$rtdr" filter --backend vulkan --in "$work/cornell" --out "$work/vulkan" > "$work/vulkan.log" 2>&1; then
    [ -f "$work/vulkan/frame_0001.exr" ] || fail "rtdr filter --backend vulkan wrote no frame_0001.exr"
  elif grep -q "^rtdr: error: Vulkan: " "$work/vulkan.log"; then  # no usable device, not a missing shader
    echo "note: no Vulkan device here; rtdr filter --backend vulkan not run"
  else
    cat "$work/vulkan.log"; fail "rtdr filter --backend vulkan from the prefix"
  fi

  # 3b. rtdr view, from the prefix: it filters, listens, and serves its page (installed in share/rtdr/view).
  "$rtdr" view --method svgf --in "$work/cornell" --port 0 > "$work/view.log" 2>&1 &
  local view_pid=$! url=""
  for _ in $(seq 1 300); do
    url=$(grep -o 'http://127\.0\.0\.1:[0-9]*/' "$work/view.log" || true)
    [ -z "$url" ] && kill -0 "$view_pid" 2> /dev/null || break
    sleep 0.2
  done
  [ -n "$url" ] || { kill "$view_pid" 2> /dev/null; cat "$work/view.log"; fail "rtdr view from the prefix did not serve"; }
  /usr/bin/python3 -c 'import sys, urllib.request; sys.exit(b"<canvas" not in urllib.request.urlopen(sys.argv[1], timeout=30).read())' \
    "$url" || { kill "$view_pid"; fail "rtdr view from the prefix serves no page at $url"; }
  kill "$view_pid"; wait "$view_pid" 2> /dev/null || true

  # 5. What the filters component brings.
  local targets="$prefix/lib/cmake/rtdr/rtdrFiltersTargets.cmake"
  if grep -n -i -E "embree|tinygltf|vulkan|openexr|imath|zlib" "$targets"; then
    fail "the filters component depends on more than it needs ($targets)"
  fi

  # 4. The example, from its installed copy: configured, built and run; prints its output, returns its status.
  local example="$prefix/share/doc/rtdr/examples/shader_port_check"
  run_example() {  # $1: a name, $2: ON or OFF for PORT_OFF_BY_ONE
    cmake -S "$example" -B "$work/$1" -G "$generator" -DCMAKE_MAKE_PROGRAM="$make_program" \
      -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_PREFIX_PATH="$prefix" \
      -DPORT_OFF_BY_ONE="$2" > "$work/$1.configure.log" 2>&1 || { cat "$work/$1.configure.log"; return 99; }
    cmake --build "$work/$1" > "$work/$1.build.log" || { cat "$work/$1.build.log"; return 99; }
    "$work/$1/shader_port_check"
  }
  local exact off exact_status off_status
  set +e
  exact=$(run_example exact OFF); exact_status=$?
  off=$(run_example off_by_one ON); off_status=$?
  set -e
  echo "$exact"
  echo "$off"
  [ "$exact_status" -eq 0 ] && grep -q "^PASS: worst difference 0$" <<< "$exact" ||
    fail "the exact port did not match the golden pass (exit $exact_status)"
  [ "$off_status" -eq 1 ] && grep -q "^FAIL: worst difference" <<< "$off" ||
    fail "the off-by-one port was not caught (exit $off_status)"
  if grep -n -i -E "imath|openexr" "$work/exact.configure.log"; then
    fail "configuring a filters-only project mentions OpenEXR or Imath ($work/exact.configure.log)"
  fi
  echo "ok: the installed rtdr rendered, evaluated, filtered and served rtdr view's page without the source tree and the build folder;" \
    "the example built, its exact port matched and its off-by-one port was caught; filters needs no OpenEXR"
}

# Inside the mount namespace: the trees hidden, then the checks.
if [ "${1:-}" = "--hidden" ]; then
  shift
  hide_source=$1 hide_build=$2
  shift 2
  mount -t tmpfs none "$hide_source"
  [ -z "$(ls -A "$hide_build" 2>/dev/null)" ] || mount -t tmpfs none "$hide_build"  # unless inside the source
  [ -z "$(ls -A "$hide_source")" ] && [ -z "$(ls -A "$hide_build" 2>/dev/null)" ] || fail "the trees are not hidden"
  checks "$@"
  exit 0
fi

build=$(realpath "$1") source=$(realpath "$2") compiler=$3 flags=$4 generator=$5 make_program=$6 launcher=${7:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
case "$work/" in "$source/"* | "$build/"*) fail "the scratch folder $work lies inside a tree it must hide" ;; esac

if unshare --mount --map-root-user true 2> /dev/null; then
  cmake --install "$build" --prefix "$prefix" > "$work/install.log" || { cat "$work/install.log"; fail "no install"; }
  cp "$0" "$work/install_package_test.sh"  # the script itself lies in the source tree it hides
  unshare --mount --map-root-user bash "$work/install_package_test.sh" --hidden "$source" "$build" \
    "$prefix" "$work" "$compiler" "$flags" "$generator" "$make_program"
  exit 0
fi

# No mount namespace here: install from a copy of the source tree, then delete the copy and its build folder.
echo "note: no mount namespace here (unshare); building rtdr again from a copy of the tree"
mkdir "$work/src"
tar -C "$source" --exclude='./build*' --exclude='./out' --exclude='./.git' --exclude='./.gl' --exclude='./.deps' \
  -cf - . | tar -C "$work/src" -xf -
cmake -S "$work/src" -B "$work/src/build" -G "$generator" -DCMAKE_MAKE_PROGRAM="$make_program" \
  -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" \
  -DCMAKE_BUILD_TYPE=Release -DRTDR_BUILD_TESTS=OFF > "$work/configure.log" ||
  { cat "$work/configure.log"; fail "the copy did not configure"; }
cmake --build "$work/src/build" --target rtdr > "$work/build.log" || { tail -40 "$work/build.log"; fail "no build"; }
cmake --install "$work/src/build" --prefix "$prefix" > "$work/install.log" ||
  { cat "$work/install.log"; fail "no install"; }
rm -rf "$work/src"
[ ! -e "$work/src" ] || fail "the copy is still there"
checks "$prefix" "$work" "$compiler" "$flags" "$generator" "$make_program"
