#!/usr/bin/env bash
# Installs the Debian 12 packages RTDR needs (only the missing ones), then configures and builds build/: every
# target, or only those named (`bash tools/setup.sh rtdr`: the command alone, as tools/demo.sh builds it).
# Idempotent: when everything is installed and built it only runs an up-to-date check of the build.
set -euo pipefail
cd "$(dirname "$0")/.."

# Every dependency is a Debian package; CMakeLists.txt finds each one by the CMake name its package installs.
PACKAGES=(
  cmake g++ pkg-config ninja-build
  libglm-dev libtinygltf-dev libopenexr-dev libimath-dev libembree-dev catch2 libtbb-dev
  libcli11-dev nlohmann-json3-dev zlib1g-dev
  # Vulkan ports (gpu/): headers and loader, build-time glslc, and lavapipe as the device where there is no GPU.
  libvulkan-dev glslc spirv-tools mesa-vulkan-drivers vulkan-validationlayers
  # Charts and notebooks run on Debian's Python (/usr/bin/python3), not whatever python3 is on PATH.
  python3-numpy python3-matplotlib python3-openimageio python3-skimage jupyter-nbconvert python3-ipykernel
  # tools/farm.py: the render jobs of `rtdr eval --plan` on a Dask cluster (docs/scaling.md).
  python3-distributed
  # rtdr view (docs/view.md): its HTTP server, the KaTeX its page typesets with, and the headless browser its test
  # drives (tests/app_view_browser_test.py).
  libcpp-httplib-dev libjs-katex chromium chromium-driver python3-selenium
)

bash tools/install_missing.sh setup "${PACKAGES[@]}"

[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
if (($#)); then
  cmake --build build --target "$@"
else
  cmake --build build
fi
