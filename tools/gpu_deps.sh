#!/usr/bin/env bash
# Fetches, on a Debian 12 machine, the packages that tools/gpu_device.sh needs on a GPU machine that has CMake and a
# compiler but no package registry: the GL/Vulkan loaders into .gl/ and the build's -dev packages (with the
# run-time libraries they pull in) into .deps/. Both folders are git-ignored; carry them to the GPU machine.
# Nothing is installed here: `apt-get download` only fetches the .deb files.
set -euo pipefail
cd "$(dirname "$0")/.."

# The Vulkan loader and the GL libraries beside it, unpacked into / there (the device tool's README).
LOADERS=(libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
# What CMakeLists.txt finds (tools/setup.sh's list, less the Python, the CPU Vulkan driver and rtdr view's packages:
# gpu_device.sh builds with -DRTDR_VIEW=OFF), and the shared libraries those -dev packages link to that a bare machine
# lacks. Unpacked into a prefix there, never into /.
DEPS=(
  libglm-dev libtinygltf-dev libtinygltf2d libstb0 libstb-dev
  libopenexr-dev libopenexr-3-1-30 libimath-dev libimath-3-1-29 zlib1g-dev
  libembree-dev libembree3-3 libtbb-dev libtbb12 libtbbmalloc2 libtbbbind-2-5 libhwloc15
  catch2 libcli11-dev nlohmann-json3-dev
  libvulkan-dev glslc libshaderc1 vulkan-validationlayers
)

rm -rf .gl .deps
mkdir -p .gl .deps
(cd .gl && apt-get download -q "${LOADERS[@]}")
(cd .deps && apt-get download -q "${DEPS[@]}")
du -sh .gl .deps
