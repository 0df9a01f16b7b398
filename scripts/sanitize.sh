#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the test suites into build-asan/
# (-O1: sanitizer-friendly and quick to compile), then runs the suites that do not need the
# GPU path: scene, metrics, reference, views and the CPU-only extremes tests (scene parsing,
# the reference far from the origin, the journal, the fuzz corpus). The GL suites are left
# out: Mesa's llvmpipe is not instrumented, and its shader compiles under ASan take longer
# than the CI budget. UB is fatal (-fno-sanitize-recover); leaks are reported.
set -euo pipefail
cd "$(dirname "$0")/.."
suites=(scene metrics reference views extremes)
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1" \
  -DLDMBENCH_SANITIZE=ON -DLDMBENCH_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build-asan -j "$(nproc)" --target "${suites[@]/#/test_}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# TBB's worker threads keep their arenas until exit; Embree's device caches likewise.
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 600 \
  -R '^(scene|metrics|reference|views)\.|^extremes\.(ExtremesScene|ExtremesReference|ExtremesJournal|FuzzCorpus)\.'
