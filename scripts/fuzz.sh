#!/usr/bin/env bash
# Builds the parser fuzzers (tests/fuzz/, libFuzzer from Debian's clang, ASan + UBSan) into
# build-fuzz/ and runs each for a fixed number of inputs from the fixed seed LDM_FUZZ_SEED
# (default 1), so that every machine, fast or slow, searches the same inputs and CI repeats
# the same search instead of failing at random on a new finding. The counts (below, per
# target; LDM_FUZZ_RUNS overrides them all) are what a 2-core machine runs in about 15 s each:
# an input of fuzz_import starts Assimp in a child process (63 inputs in 30 s), one of
# fuzz_scene_json parses a few hundred bytes (100,000 in under 30 s). LDM_FUZZ_SECONDS
# (default 300) only bounds a target on a far slower machine, and the script says so when a
# target stopped at it before its count. Explore with another seed and more runs by hand. A
# crash, hang or sanitizer report is copied to tests/fuzz/crashes/<target>/ and fails the
# script. The targets run LDM_FUZZ_JOBS at a time (default: the number of cores).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${LDM_FUZZ_SECONDS:-300}"
declare -A runs_of=([scene_json]=50000 [obj]=400 [import]=30 [sweep]=50000 [records]=5000)
seed="${LDM_FUZZ_SEED:-1}"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLDMBENCH_BUILD_TESTS=OFF -DLDMBENCH_BUILD_BENCHMARKS=OFF -DLDMBENCH_FUZZ=ON > /dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_scene_json fuzz_obj fuzz_import fuzz_sweep fuzz_records
# The targets run side by side, as many at once as there are cores (LDM_FUZZ_JOBS): each is
# bounded by its own time and run count, so running them together changes nothing but the
# step's wall time (5 x 30 s one after another was 150 s; on 2 cores it is 90 s).
jobs="${LDM_FUZZ_JOBS:-$(nproc)}"
targets=(scene_json obj import sweep records)
fuzz_one() {
  local target=$1 corpus="build-fuzz/corpus/$1" artifacts="build-fuzz/artifacts/$1/"
  mkdir -p "$corpus" "$artifacts"
  (cd build-fuzz && "tests/fuzz/fuzz_$target" -max_total_time="$seconds" -runs="${LDM_FUZZ_RUNS:-${runs_of[$target]}}" -seed="$seed" -timeout=10 \
      -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="../$artifacts" \
      "../$corpus" "../tests/fuzz/corpus/$target") > "build-fuzz/fuzz_$target.log" 2>&1
}
declare -A pid_of
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  echo "fuzz: $target for ${LDM_FUZZ_RUNS:-${runs_of[$target]}} inputs (at most ${seconds} s)"
  fuzz_one "$target" &
  pid_of[$target]=$!
done
# Reported in a fixed order, whichever ended first.
status=0
for target in "${targets[@]}"; do
  if ! wait "${pid_of[$target]}"; then
    tail -n 40 "build-fuzz/fuzz_$target.log"
    mkdir -p "tests/fuzz/crashes/$target"
    cp "build-fuzz/artifacts/$target/"* "tests/fuzz/crashes/$target/" 2>/dev/null || true
    echo "fuzz: $target FAILED; inputs copied to tests/fuzz/crashes/$target/"
    status=1
  else
    echo "fuzz: $target"
    grep -E "^stat::number_of_executed_units|^Done" "build-fuzz/fuzz_$target.log" || true
    executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "build-fuzz/fuzz_$target.log" | tail -n 1)
    if [ -n "$executed" ] && [ "$executed" -lt "${LDM_FUZZ_RUNS:-${runs_of[$target]}}" ]; then
      echo "fuzz: $target stopped at its ${seconds} s bound after $executed of ${LDM_FUZZ_RUNS:-${runs_of[$target]}} inputs (a slow machine: this run searched fewer inputs than CI's)"
    fi
  fi
done
exit $status
