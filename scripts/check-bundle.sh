#!/usr/bin/env bash
# CI step (.ci/run): makes the GPU-node bundle (scripts/bundle.sh) from this machine's build
# and checks that it is what docs/guide/gpu-nodes.md promises:
#   1. at most 60 MiB;
#   2. it works moved: the bundle is copied to another path and the original renamed away,
#      so that any path into the original would fail;
#   3. from there, every library each binary and bundled library loads resolves inside the
#      bundle or to the node's own (the GPU driver's and the C library's: bundle.sh's list),
#      and nothing is "not found"; a copy with one library removed must fail this check;
#   4. ldmbench info, a tiny run of a bundled scene file with a bundled model (repetitions in
#      their own processes: ldmbench runs itself again), ldmbench_gbench;
#   5. gpu-suite.sh --dry-run from the moved bundle, end to end; its time guard stopping and
#      skipping steps; the full-size sweeps enumerating (--plan).
#   scripts/check-bundle.sh [--keep] [--from TARBALL]
#   (--keep leaves the work folder for inspection; --from checks a bundle.sh --tar tarball
#   instead of making one)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
keep=0
from=""
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) keep=1; shift ;;
    --from) from="$(realpath "$2")"; shift 2 ;;
    *) echo "check-bundle.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
work="$(mktemp -d /tmp/ldm-check-bundle.XXXXXX)"
cleanup() { [ "$keep" = 1 ] && echo "check-bundle: work folder kept: $work" || rm -rf "$work"; }
trap cleanup EXIT
t0=$(date +%s)
step() { echo "check-bundle [$(( $(date +%s) - t0 ))s] $*"; }
fail() { echo "check-bundle: FAILED: $*" >&2; exit 1; }

made="$work/made/ldmbench"
if [ -n "$from" ]; then
  step "unpacking $from"
  mkdir -p "$work/made" && tar -C "$work/made" -xJf "$from" && cp "$from" "$made.tar.xz"
else
  step "making the bundle"
  # The tarball here is only unpacked again, never shipped: the fastest xz level (the packed
  # libraries inside keep bundle.sh's own -6, so the 60 MiB check below is unchanged).
  XZ_OPT="${XZ_OPT:--T0 -0}" "$root/scripts/bundle.sh" "$made" --tar
fi
size=$(du -sb "$made" | cut -f1)
[ "$size" -le $((60 << 20)) ] || fail "the bundle is $((size >> 20)) MiB, over 60 MiB"
tar_size=$(stat -c %s "$made.tar.xz")

step "moving it: unpacked from its tarball elsewhere, the original renamed away"
moved="$work/elsewhere/some where/ldmbench"  # a space in the path, too
mkdir -p "$(dirname "$moved")"
tar -C "$(dirname "$moved")" -xJf "$made.tar.xz"
mv "$made" "$work/made/original-gone"
unset LD_LIBRARY_PATH

step "ldmbench info (unpacks the packed libraries)"
"$moved/bin/ldmbench" info | tee "$work/info.txt"
grep -q '^renderer: ' "$work/info.txt" || fail "ldmbench info printed no renderer"
[ -z "$(ls "$moved/lib/packed")" ] || for p in "$moved"/lib/packed/*.xz; do
  [ -f "$moved/lib/$(basename "$p" .xz)" ] || fail "$(basename "$p") was not unpacked"
done

# The node's libraries: the same list bundle.sh leaves out.
node_lib_pattern="$(sed -n "s/^node_lib_pattern='\(.*\)'$/\1/p" "$root/scripts/bundle.sh")"
[ -n "$node_lib_pattern" ] || fail "cannot read node_lib_pattern from scripts/bundle.sh"
# Prints each library of each ELF file under BUNDLE that resolves outside it and is not
# the node's, or is not found; says how many objects it looked at.
foreign_libraries() {
  local bundle="$1" n=0 f
  while IFS= read -r -d '' f; do
    [ "$(head -c 4 "$f" | tail -c 3)" = ELF ] || continue
    n=$((n + 1))
    ldd "$f" | sed -n -E 's/^[[:space:]]*([^ ]+) => (not found|(.*) \(0x[0-9a-f]+\))$/\1\t\2/p' |
      while IFS=$'\t' read -r name path; do
        if [ "$path" = "not found" ]; then echo "$f: $name not found"; continue; fi
        path="${path% (0x*}"
        case "$path" in "$bundle"/*) continue ;; esac
        [[ "$name" =~ $node_lib_pattern ]] || echo "$f: $name => $path (outside the bundle, not the node's)"
      done
  done < <(find "$bundle/libexec" "$bundle/lib" -maxdepth 2 -type f -print0)
  echo "checked $n objects" >&2
}
step "ldd of every binary and library: inside the bundle or the node's"
bad="$(foreign_libraries "$moved")"
[ -z "$bad" ] || fail "libraries outside the bundle:"$'\n'"$bad"
step "... and the check can fail: a copy without libpng16"
broken="$work/broken/ldmbench"
mkdir -p "$work/broken" && cp -a "$moved" "$broken" && rm "$broken/lib/libpng16.so.16"
foreign_libraries "$broken" | grep -q 'libpng16.so.16 => /' || fail "a missing bundled library went unnoticed"

step "a tiny run of a bundled scene with a bundled model, repetitions in their own processes"
cd "$work"  # not the source tree: nothing may come from it
"$moved/bin/ldmbench" run --scene "$moved/scenes/teapots.json" --structure psppsll,habuffer -N 4 -R 16 \
  --image-size 32x24 --frames 1 --warmup 0 --reference-spp 8 --repetitions 2 --isolation process \
  --cache-dir "$work/cache" --out "$work/run" | tail -3
ok=$(grep -c ',ok,' "$work/run/records.csv" || true)
[ "$ok" = 2 ] || fail "the tiny run recorded $ok ok configurations, not 2 ($work/run/records.csv)"
"$moved/bin/ldmbench_gbench" --benchmark_list_tests > "$work/gbench.txt" || fail "ldmbench_gbench did not run"
[ -s "$work/gbench.txt" ] || fail "ldmbench_gbench listed no benchmarks"

step "gpu-suite.sh --dry-run from the moved bundle"
"$moved/gpu-suite.sh" --dry-run --out "$work/records" > "$work/suite.txt" 2>&1 || { cat "$work/suite.txt"; fail "gpu-suite.sh --dry-run failed"; }
summary="$(ls "$work"/records/*/summary.md)"
grep -q '^| gpu-tests | ok ' "$summary" || fail "the dry run's tests did not pass ($summary)"
grep -q '^| ao | ok ' "$summary" || fail "the dry run's AO step did not finish ($summary)"
grep -q '^| indirect | ok ' "$summary" || fail "the dry run's indirect step did not finish ($summary)"
sed -n '/^| step/,/^$/p' "$summary"

step "its time guard: a step over its share is stopped, one that cannot fit is skipped"
# Held steps wait 600 s before their work (--hold), so they outlast their 1 s and 3 s limits
# on any machine; the indirect step's 1000 s estimate cannot fit a 300 s budget. Nothing here
# depends on how fast the machine is.
"$moved/gpu-suite.sh" --dry-run --budget 300 --estimates gpu-tests=1,ao=3,indirect=1000 \
  --hold gpu-tests=600,ao=600 --out "$work/guard" > "$work/guard.txt" 2>&1 ||
  { cat "$work/guard.txt"; fail "gpu-suite.sh under a short budget failed"; }
summary="$(ls "$work"/guard/*/summary.md)"
grep -q '^| gpu-tests | stopped ' "$summary" || fail "the held test step was not stopped at its 1 s limit ($summary)"
grep -q '^| ao | stopped | 3 | 3 ' "$summary" || fail "the held AO step was not stopped at its 3 s limit ($summary)"
grep -q '^| indirect | skipped ' "$summary" || fail "the indirect step was not skipped ($summary)"
step "bad arguments: exit 2, nothing written"
rc=0; "$moved/gpu-suite.sh" --estimates foo=3 --out "$work/bad" 2> "$work/bad.txt" || rc=$?
[ "$rc" = 2 ] && [ ! -e "$work/bad" ] && grep -q "no step 'foo'" "$work/bad.txt" ||
  fail "gpu-suite.sh --estimates foo=3: exit $rc, $(ls "$work/bad" 2>/dev/null | wc -l) files, '$(cat "$work/bad.txt")'"
rc=0; "$moved/gpu-suite.sh" --hold ao=soon --out "$work/bad" 2> "$work/bad.txt" || rc=$?
[ "$rc" = 2 ] && [ ! -e "$work/bad" ] && grep -q "not STEP=SECONDS" "$work/bad.txt" ||
  fail "gpu-suite.sh --hold ao=soon: exit $rc, $(ls "$work/bad" 2>/dev/null | wc -l) files, '$(cat "$work/bad.txt")'"
step "the full-size plan: its sweeps enumerate"
"$moved/gpu-suite.sh" --plan --out "$work/plan" | tee "$work/plan.txt"
grep -q -E 'ao [0-9]+ configurations x 3 repetitions at 1280x720' "$work/plan.txt" || fail "no full-size plan"
echo "check-bundle: ok in $(( $(date +%s) - t0 )) s: bundle $((size * 10 / 1048576 / 10)).$((size * 10 / 1048576 % 10)) MiB, tarball $((tar_size >> 20)) MiB"
