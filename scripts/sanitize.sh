#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the test suites into build-asan/
# (-O0, the quickest to compile, except the path tracer, harness/reference, at -O1: these
# suites spend most of their time in it. Measured on 2 cores: 248 s for the step, against 295 s
# with everything at -O1 and 426 s with everything at -O0; docs/testing.md#build-time), then
# runs the suites that do not need the
# GPU path: scene, import (the mesh importer, Assimp in its child process), metrics,
# reference, views, stats (the timing statistics), compare's verdicts on synthetic runs,
# and the CPU-only extremes tests (scene parsing, the reference far from
# the origin, the journal, the fuzz corpus). The GL suites are left
# out: Mesa's llvmpipe is not instrumented, and its shader compiles under ASan take longer
# than the CI budget. UB is fatal (-fno-sanitize-recover). Leak checking is off: every test
# process, even one that never touches the GPU, reports the same 128-byte realloc from a
# library already unloaded at exit ("<unknown module>"; presumably one of the GL/EGL loader
# libraries every binary links), which no suppression can name.
set -euo pipefail
cd "$(dirname "$0")/.."
suites=(scene import metrics reference views stats compare extremes)
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O0" \
  -DLDMBENCH_O1_FOLDERS=harness/reference \
  -DLDMBENCH_SANITIZE=ON -DLDMBENCH_BUILD_BENCHMARKS=OFF -DLDMBENCH_TESTS_BUILD_BINARIES=OFF > /dev/null
# Only the suites below and what they link (not ldmbench, the viewer or the GL suites): none
# of the tests run here starts ldmbench.
cmake --build build-asan -j "$(nproc)" --target "${suites[@]/#/test_}"
export ASAN_OPTIONS="detect_leaks=0:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 600 \
  -R '^(scene|import|metrics|reference|views|stats)\.|^compare\.(CompareRuns|Samples)\.|^extremes\.(ExtremesScene|ExtremesReference|ExtremesJournal|FuzzCorpus)\.'
