#!/usr/bin/env bash
# Installs the dependencies, builds ldmbench and runs the main job: PSPPSLL ambient occlusion
# on the embedded default scene (the Cornell box). Extra arguments go to `ldmbench run`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
build/ldmbench run --scene cornell --structure psppsll --pass ao "$@"
