#!/usr/bin/env bash
# CI step (.ci/run): the test suites that do GPU work in their own process (a GL context of
# their own: structures, contention, passes, indirect, sizing, ...) again under Mesa's second
# OpenGL driver for CPUs, zink over the Vulkan driver lavapipe: GLSL through SPIR-V, 64-bit
# atomics (the HA-buffer's 64-bit keys, which skip on llvmpipe), compute-shader races.
# scripts/test.sh has run the whole suite under llvmpipe (the cross-driver comparison,
# tests/drivers, among it) and built build/.
#   scripts/zink-tests.sh [BUILD_DIR]
# Then the known driver defect's reproducer (docs/reference/structures.md#driver-conformance),
# whose outcome is printed, not judged: it fails while Mesa's lavapipe has the defect.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
t0=$(date +%s)
export XDG_RUNTIME_DIR="$(mktemp -d /tmp/ldm-zink-runtime.XXXXXX)"
trap 'rm -rf "$XDG_RUNTIME_DIR"' EXIT
export MESA_LOADER_DRIVER_OVERRIDE=zink LIBGL_ALWAYS_SOFTWARE=1
renderer="$("$build/ldmbench" info | sed -n 's/^renderer: //p')"
case "$renderer" in
  zink*) echo "zink-tests: $renderer" ;;
  *) echo "zink-tests: FAILED: ldmbench opened '$renderer', not zink (are mesa-vulkan-drivers and libvulkan1 installed? scripts/setup.sh)" >&2; exit 1 ;;
esac
"$build/ldmbench" info | grep '^self-test' || true
# The suites whose tests build structures or run passes in the test process itself.
suites='ao|context|extremes|indirect|measure|passes|peers|psppsll|sizing|structures|work'
# extremes' CPU-only cases (scene parsing, the reference far from the origin, the journal, the
# fuzz corpus) touch no driver: test.sh and sanitize.sh run them; not a third time here.
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900 \
  -R "^($suites)\\." -E 'DriverDefects\.|^extremes\.(ExtremesScene|ExtremesReference|ExtremesJournal|FuzzCorpus)\.'
echo "zink-tests: the reproducer of the known driver defect (reported, not judged):"
if "$build/tests/test_context" --gtest_filter='DriverDefects.*' > "$XDG_RUNTIME_DIR/defects.txt" 2>&1; then
  echo "  passes: this zink has no barrier defect (docs/reference/structures.md#driver-conformance is out of date)"
else
  grep -E 'invocations lost' "$XDG_RUNTIME_DIR/defects.txt" | sed 's/^/  /' | head -3
fi
echo "zink-tests: ok in $(( $(date +%s) - t0 )) s"
