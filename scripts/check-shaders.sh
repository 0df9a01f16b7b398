#!/usr/bin/env bash
# CI step (.ci/run): every shader program ldmbench builds, compiled again by glslang, the
# Khronos reference GLSL front end (llvmpipe and zink share Mesa's compiler; NVIDIA's and
# AMD's are their own). Runs a covering sweep generated from `ldmbench axes --json` (every
# structure x pass, every other axis value one at a time, at tiny sizes), the test binaries
# that build compute-only programs, and the viewer, under llvmpipe and under zink, with
# LDM_SHADER_DUMP set; then checks that every shader file and every preprocessor branch was
# compiled, and runs glslangValidator on every dumped program (docs/guide/testing.md#glslang).
#   scripts/check-shaders.sh [BUILD_DIR]          (build/ by default; scripts/test.sh builds it)
# Exit 0: all accepted; 1: glslang rejected something or the runs missed a variant (the
# message names the dumped file and the shader file and line); 2: the check could not run.
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
status=0
/usr/bin/python3 scripts/check_shaders.py --build "${1:-build}" || status=$?
echo "check-shaders: $([ "$status" -eq 0 ] && echo ok || echo "FAILED (exit $status)") in $(( $(date +%s) - t0 )) s"
exit "$status"
