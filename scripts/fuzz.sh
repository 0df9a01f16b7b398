#!/usr/bin/env bash
# Builds the parser fuzzers (tests/fuzz/, libFuzzer from Debian's clang, ASan + UBSan) into
# build-fuzz/ and runs each for LDM_FUZZ_RUNS inputs (default 100000) or LDM_FUZZ_SECONDS
# seconds (default 30), whichever ends first, from the fixed seed LDM_FUZZ_SEED (default 1),
# so that CI repeats the same search instead of failing at random on a new finding; explore
# with another seed and more runs by hand. A crash, hang or sanitizer report is copied to
# tests/fuzz/crashes/<target>/ and fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${LDM_FUZZ_SECONDS:-30}"
runs="${LDM_FUZZ_RUNS:-100000}"
seed="${LDM_FUZZ_SEED:-1}"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLDMBENCH_BUILD_TESTS=OFF -DLDMBENCH_BUILD_BENCHMARKS=OFF -DLDMBENCH_FUZZ=ON > /dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_scene_json fuzz_obj fuzz_import fuzz_sweep fuzz_records
status=0
for target in scene_json obj import sweep records; do
  corpus="build-fuzz/corpus/$target" artifacts="build-fuzz/artifacts/$target/"
  mkdir -p "$corpus" "$artifacts"
  echo "fuzz: $target for ${seconds}s"
  if ! (cd build-fuzz && "tests/fuzz/fuzz_$target" -max_total_time="$seconds" -runs="$runs" -seed="$seed" -timeout=10 \
          -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="../$artifacts" \
          "../$corpus" "../tests/fuzz/corpus/$target") > "build-fuzz/fuzz_$target.log" 2>&1; then
    tail -n 40 "build-fuzz/fuzz_$target.log"
    mkdir -p "tests/fuzz/crashes/$target"
    cp "$artifacts"* "tests/fuzz/crashes/$target/" 2>/dev/null || true
    echo "fuzz: $target FAILED; inputs copied to tests/fuzz/crashes/$target/"
    status=1
  else
    grep -E "^stat::number_of_executed_units|^Done" "build-fuzz/fuzz_$target.log" || true
  fi
done
exit $status
