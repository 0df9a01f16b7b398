#!/usr/bin/env bash
# Installs every Debian package ldmbench needs to build, test and plot.
# Idempotent: packages already present are skipped by apt; safe to run again.
set -euo pipefail

packages=(
  # toolchain
  cmake ninja-build g++ pkg-config git
  # parser fuzzing (scripts/fuzz.sh): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
  # headless OpenGL 4.5: libglvnd's EGL/OpenGL plus Mesa's llvmpipe for machines without a GPU
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # the second driver the tests run under: zink over the Vulkan driver lavapipe
  # (scripts/zink-tests.sh, tests/drivers)
  mesa-vulkan-drivers libvulkan1
  # the second GLSL front end (scripts/check-shaders.sh): glslangValidator, Khronos' reference
  # compiler, on every shader program the harness builds
  glslang-tools
  # `ldmbench view`: GLFW and Dear ImGui (GLFW + OpenGL 3 backends), and for its tests a
  # virtual X server (xvfb-run needs xauth) and xdotool to type into the window
  libglfw3-dev libimgui-dev xvfb xauth xdotool
  # the man page's rendering test (groff -man -ww, tests/cli/docs_test.cpp)
  groff-base
  # libraries
  libglm-dev libopenexr-dev libpng-dev libembree-dev libtbb-dev
  nlohmann-json3-dev libcli11-dev
  # mesh files of every common format (glTF/GLB, PLY, FBX, Collada, 3DS, STL, OFF, OBJ, IFC)
  libassimp-dev
  # real-world models referenced by scenes/ (installed under /usr/share/assimp/models)
  assimp-testmodels
  libgtest-dev libgmock-dev libbenchmark-dev
  # scripts/bundle.sh: RUNPATH $ORIGIN on the bundled binaries and libraries, and xz for its
  # packed libraries and tarball (priority standard: not on every minimal image)
  patchelf xz-utils
  # distributions for the timing statistics (harness/stats: binomial, Student t, non-central t)
  libboost-math-dev
  # Google Benchmark's compare.py (/usr/share/benchmark/compare.py) for ldmbench_gbench JSON
  libbenchmark-tools
  # independent metric oracle (skimage) and report plots
  python3 python3-numpy python3-scipy python3-skimage python3-matplotlib python3-pandas
  # the report: HDR images tone-mapped from their EXR (python3-openimageio), and its HTML
  # tested in a real browser (tests/report/browser_check.py: headless chromium, with fonts)
  python3-openimageio chromium fonts-dejavu-core
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
