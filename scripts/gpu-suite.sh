#!/usr/bin/env bash
# The GPU suite (docs/guide/gpu-nodes.md): on one GPU, within a time budget, the tests that
# only a GPU can check, then the headline tables with repetitions, into a folder named after
# the device. Runs from the bundle (scripts/bundle.sh: ./gpu-suite.sh beside bin/) or from
# a source tree with a build (scripts/gpu-suite.sh, binaries in build/ or $LDM_BUILD).
#
#   gpu-suite.sh [--out DIR] [--budget SECONDS] [--dry-run]
#
#   --out DIR         records go to DIR/<device>/ (default: ./gpu-records); a rerun resumes
#   --budget SECONDS  the whole suite's time (default 540: 9 minutes, so that with the
#                     bundle's start it fits in 10); a step that cannot finish in what is left
#                     is skipped, and a step that overruns its share is stopped, each with a
#                     note in the summary (its records so far are kept; a rerun resumes)
#   --dry-run         the same steps at tiny sizes (any OpenGL 4.5 device, llvmpipe too): CI
#   --plan            write the sweep files, print each step's configurations and estimate,
#                     run nothing
#   --estimates gpu-tests=S,ao=S,indirect=S
#                     replace the steps' time estimates (seconds), e.g. by the times a
#                     previous run's steps.tsv measured on this device
#   --hold STEP=S,... make a step wait S seconds before it starts its work, inside its time
#                     limit (for testing the time guard: a held step provably outlasts a
#                     limit shorter than S, however fast the machine)
#
# Steps: 1 gpu-tests (the 64-bit HA-buffer keys, every structure's contention test, the
# timestamp timer against the wall clock), 2 ao (AO on the Cornell box and the atrium, every
# structure, N 16..128 and R_LDM 200..512 at 1280x720, with the peers HBAO and RTAO),
# 3 indirect (indirect light, the same scenes and structures). Writes DIR/<device>/summary.md
# (what ran, what was skipped or stopped and why, estimated and actual seconds) and
# steps.tsv. Exit status: 0 when every step that ran passed (a step skipped or stopped by the
# time guard is noted, not a failure), 1 when a test failed or a step could not run, 2 for
# bad arguments, 3 when the tables finished with some configurations failed or invalid (on
# a GPU, e.g. a structure over the device's storage block: the records say which and why).
set -uo pipefail

out_root="gpu-records"
budget=540
dry_run=0
plan=0
estimates=""
holds=""
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out_root="${2:?--out needs a folder}"; shift 2 ;;
    --budget) budget="${2:?--budget needs seconds}"; shift 2 ;;
    --dry-run) dry_run=1; shift ;;
    --plan) plan=1; shift ;;
    --estimates) estimates="${2:?--estimates needs STEP=SECONDS,...}"; shift 2 ;;
    --hold) holds="${2:?--hold needs STEP=SECONDS,...}"; shift 2 ;;
    -h|--help) sed -n '2,32p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "gpu-suite.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$budget" in ''|*[!0-9]*) echo "gpu-suite.sh: --budget '$budget' is not a whole number of seconds" >&2; exit 2 ;; esac
# Checked before anything is written.
override_tests=""; override_ao=""; override_indirect=""
hold_tests=0; hold_ao=0; hold_indirect=0
# STEP=SECONDS pairs of OPTION into the variables named PREFIX_tests, PREFIX_ao, PREFIX_indirect.
parse_step_seconds() {  # OPTION PAIRS PREFIX
  local pair seconds
  for pair in ${2//,/ }; do
    seconds="${pair#*=}"
    case "$seconds" in ''|*[!0-9]*) echo "gpu-suite.sh: $1 '$pair': not STEP=SECONDS" >&2; exit 2 ;; esac
    case "${pair%%=*}" in
      gpu-tests) printf -v "$3_tests" '%s' "$seconds" ;;
      ao) printf -v "$3_ao" '%s' "$seconds" ;;
      indirect) printf -v "$3_indirect" '%s' "$seconds" ;;
      *) echo "gpu-suite.sh: $1 '$pair': no step '${pair%%=*}' (gpu-tests, ao, indirect)" >&2; exit 2 ;;
    esac
  done
}
parse_step_seconds --estimates "$estimates" override
parse_step_seconds --hold "$holds" hold
start=$(date +%s)

# Where the binaries are: the bundle's launchers, else a build of this source tree.
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ -x "$here/bin/ldmbench" ]; then
  ldmbench="$here/bin/ldmbench"
  test_bin="$here/bin"
  data="$here"
else
  build="${LDM_BUILD:-$here/../build}"
  ldmbench="$build/ldmbench"
  test_bin="$build/tests"
  data="$here/.."
fi
[ -x "$ldmbench" ] || { echo "gpu-suite.sh: no ldmbench at $ldmbench (build it, or run the bundle's gpu-suite.sh)" >&2; exit 1; }

# The device names the folder: its GL renderer, lower case, runs of other characters as '-'.
info="$("$ldmbench" info 2>&1)" || { echo "gpu-suite.sh: ldmbench info failed:" >&2; echo "$info" >&2; exit 1; }
renderer="$(printf '%s\n' "$info" | sed -n 's/^renderer: //p')"
device="$(printf '%s' "$renderer" | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9]\{1,\}/-/g; s/^-//; s/-$//' | cut -c1-60)"
[ -n "$device" ] || device="unknown-device"
dir="$out_root/$device"
mkdir -p "$dir" || exit 1
dir="$(cd "$dir" && pwd)"
printf '%s\n' "$info" > "$dir/info.txt"
cache="$dir/reference-cache"
: > "$dir/steps.tsv"
printf 'step\tstatus\testimate_s\tlimit_s\tactual_s\tnote\n' >> "$dir/steps.tsv"
failed=0
some_failed=0

elapsed() { echo $(( $(date +%s) - start )); }
log() { echo "gpu-suite [$(elapsed)s/${budget}s] $*"; }
record_step() {  # name status estimate limit actual note
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$@" >> "$dir/steps.tsv"
  log "$1: $2 ($5 s of an estimated $3 s, limit $4 s)${6:+: $6}"
}

# Runs one step under the time guard. Each step's estimate is what its sizes should take on
# one datacentre GPU (a guess until a first GPU run's steps.tsv calibrates it) or, in the dry
# run, on llvmpipe with 2 cores. Earlier steps come first: a step starts if its estimate fits
# in what is left, and may run until what is left less the estimates of the steps after it
# (but at least its own estimate), so that its overrun cannot take their time.
#   guarded NAME ESTIMATE RESERVE_AFTER HOLD COMMAND...
# (HOLD: seconds the step waits, inside its limit, before its command: --hold)
guarded() {
  local name="$1" estimate="$2" reserve="$3" hold="$4"
  shift 4
  local left=$(( budget - $(elapsed) ))
  if [ "$left" -lt "$estimate" ]; then
    record_step "$name" skipped "$estimate" "$left" 0 "not started: ${left} s left, ${estimate} s estimated"
    return 0
  fi
  left=$(( left - reserve ))
  [ "$left" -ge "$estimate" ] || left="$estimate"
  local t0 rc
  t0=$(date +%s)
  timeout --signal=TERM --kill-after=20 "$left" bash -c 'sleep "$0" && "$@"' "$hold" "$@" > "$dir/$name.log" 2>&1
  rc=$?
  local took=$(( $(date +%s) - t0 ))
  if [ "$rc" = 124 ] || [ "$rc" = 137 ]; then
    record_step "$name" stopped "$estimate" "$left" "$took" "stopped by the time guard at ${left} s; records so far are kept, a rerun resumes ($name.log)"
  elif [ "$rc" = 3 ]; then  # ldmbench's kExitSomeFailed: the sweep finished
    record_step "$name" some-failed "$estimate" "$left" "$took" "finished; some records are failed or invalid, each says why in status_detail"
    some_failed=1
  elif [ "$rc" != 0 ]; then
    record_step "$name" failed "$estimate" "$left" "$took" "exit status $rc ($name.log)"
    failed=1
  else
    record_step "$name" ok "$estimate" "$left" "$took" ""
  fi
}

# Step sizes. Real: thesis-sized (N 16..128, R_LDM 200..512, 1280x720), 3 repetitions each
# in its own GL context, round robin, fixed frame counts (no adaptive frames: their time
# would be the GPU's to choose). Dry run: the same sweeps, tiny.
if [ "$dry_run" = 1 ]; then
  image="32x24"; reps=2; frames=1; warmup=0
  # Each varied axis on one scene only: every structure's shaders compile once per
  # configuration, which is most of a configuration's time on llvmpipe.
  n_scenes='"scenes": "cornell", '; r_scenes='"scenes": "atrium", '
  ao_base_n=4; ao_ns='[8]'; ao_base_r=16; ao_rs='[24]'; ao_spp=32
  ind_base_n=4; ind_ns='[8]'; ind_base_r=16; ind_rs='[24]'; ind_light=16
  ind_reference='{"max_spp": 16}'  # the reference path end to end, tiny
  # llvmpipe on 2 cores: shader compilation is most of a run
  est_tests=10; run_ms=600; ao_reference_s=2; indirect_reference_s=2
else
  image="1280x720"; reps=3; frames=5; warmup=2; n_scenes=""; r_scenes=""
  ao_base_n=32; ao_ns='[16, 64, 128]'; ao_base_r=256; ao_rs='[200, 512]'; ao_spp=1024
  ind_base_n=32; ind_ns='[16, 64]'; ind_base_r=256; ind_rs='[512]'; ind_light=256
  # No indirect reference at full size: path-traced at 1280x720 it took 130 s per scene on
  # an H200 node's 16 cores, more than the step's frames, and its error is the same on any
  # device (the images are); measure it at home, at any size (docs/measured/indirect.md).
  ind_reference='{"enabled": false}'
  # Measured on an NVIDIA H200 with 16 CPU cores (docs/measured/gpu-suite.md): the tests
  # 10 s; 1.23 s per configuration and repetition (GL context, census, 7 frames, counting
  # replay, metrics and images of a 1280x720 frame); the AO references within that; the
  # indirect references (2 x up to 128 spp path-traced at 1280x720) took about 130 s per
  # scene on the node's CPU cores, before the step's first frame: they are left out now.
  est_tests=15; run_ms=1250; ao_reference_s=20; indirect_reference_s=0
fi


# The clock warm-up's limit per repetition (docs/timing.md): on the H200 the clock rose from
# idle within a few frames of load, and 252 repetitions at the default 3 s each would take
# the AO step's whole budget if a GPU never reached its working clock; a repetition that
# does not is warned about in its record.
clock_warmup_s=1.5

write_ao_sweep() {
  cat > "$dir/ao-sweep.json" <<EOF
{
  "description": "gpu-suite.sh: AO on the Cornell box and the atrium, every structure, N and R_LDM each varied around N = $ao_base_n, R_LDM = $ao_base_r, $image images, the peers HBAO, GTAO, GPU RTAO (1, 4, 16 spp) and the CPU RTAO at the base point",
  "axes": {
    "scenes": ["cornell", "atrium"],
    "passes": "ao",
    "structures": "all",
    "views": $ao_base_n,
    "r_ldm": $ao_base_r,
    "image_size": "$image",
    "frames": $frames,
    "warmup": $warmup
  },
  "include": [
    {"comment": "N (thesis Table 3)", $n_scenes"views": $ao_ns},
    {"comment": "R_LDM (Table 4)", $r_scenes"r_ldm": $ao_rs},
    {"comment": "the peers, which read no LDM", "passes": ["hbao", "gtao", "rtao"]},
    {"comment": "GPU RTAO at 1, 4 and 16 rays per pixel (its BVH built once per scene)", "passes": "rtao_gpu", "rtao_gpu:spp": [1, 4, 16]}
  ],
  "settings": {"reference": {"max_spp": $ao_spp}, "timing": {"target": 0, "clock_warmup_s": $clock_warmup_s}}
}
EOF
}

write_indirect_sweep() {
  cat > "$dir/indirect-sweep.json" <<EOF
{
  "description": "gpu-suite.sh: indirect light on the Cornell box and the atrium, every structure, N and R_LDM varied around N = $ind_base_n, R_LDM = $ind_base_r, R_light = $ind_light, $image images",
  "axes": {
    "scenes": ["cornell", "atrium"],
    "passes": "indirect",
    "structures": "all",
    "views": $ind_base_n,
    "r_ldm": $ind_base_r,
    "indirect:r_light": $ind_light,
    "image_size": "$image",
    "frames": $frames,
    "warmup": $warmup
  },
  "include": [
    {"comment": "N (thesis Table 6)", $n_scenes"views": $ind_ns},
    {"comment": "R_LDM (Table 8)", $r_scenes"r_ldm": $ind_rs}
  ],
  "settings": {"reference": $ind_reference, "timing": {"target": 0, "clock_warmup_s": $clock_warmup_s}}
}
EOF
}

# Step 1: the tests only a GPU can check (on llvmpipe they run too, or skip where a software
# renderer has nothing to show: see each test's comment).
gpu_tests() {
  local rc=0
  "$test_bin/test_context" --gtest_output="xml:$dir/tests/test_context.xml" || rc=1
  "$test_bin/test_structures" --gtest_output="xml:$dir/tests/test_structures.xml" \
    --gtest_filter='HaBuffer.SixtyFourBitKeys*:HaBuffer.DefaultKeys*:*/Contention.*:ContentionSource.*' || rc=1
  return $rc
}

sweep() {  # NAME: runs DIR/NAME-sweep.json into DIR/NAME
  "$ldmbench" sweep "$dir/$1-sweep.json" --out "$dir/$1" --repetitions "$reps" --cache-dir "$cache"
}

# The time guard runs each step as its own process group (timeout signals all of it).
export -f gpu_tests sweep
export dir test_bin ldmbench reps cache
mkdir -p "$dir/tests"
write_ao_sweep
write_indirect_sweep
# A step's estimate: its configurations (as the sweep enumerates them) times the
# repetitions times the cost of one run, plus its references.
configurations() {  # NAME
  "$ldmbench" sweep "$dir/$1-sweep.json" --dry-run | grep -c $'^[0-9][0-9]*\t'
}
ao_configs="$(configurations ao)" && indirect_configs="$(configurations indirect)" ||
  { echo "gpu-suite.sh: ldmbench cannot enumerate the suite's sweeps ($dir/*-sweep.json)" >&2; exit 1; }
est_ao=$(( ao_configs * reps * run_ms / 1000 + ao_reference_s ))
est_indirect=$(( indirect_configs * reps * run_ms / 1000 + indirect_reference_s ))
est_tests="${override_tests:-$est_tests}"; est_ao="${override_ao:-$est_ao}"; est_indirect="${override_indirect:-$est_indirect}"
log "device '$renderer' -> $dir$([ "$dry_run" = 1 ] && echo ' (dry run: tiny sizes)')"
log "plan: gpu-tests ~${est_tests} s; ao $ao_configs configurations x $reps repetitions at $image ~${est_ao} s; indirect $indirect_configs x $reps ~${est_indirect} s; budget $budget s"
if [ "$dry_run" = 0 ] && grep -q -i -E 'llvmpipe|softpipe|swrast|software' <<< "$renderer"; then
  log "warning: full sizes on a software renderer: the time guard will skip or stop most of it (--dry-run is the small version)"
fi
if [ "$plan" = 1 ]; then
  [ $(( est_tests + est_ao + est_indirect )) -le "$budget" ] || log "plan: the estimates exceed the budget: the time guard will skip or stop steps"
  exit 0
fi
# Reserves: what each later step needs at least to start (its estimate), so that an overrun
# of the AO tables cannot starve the indirect ones of their start.
guarded gpu-tests "$est_tests" $(( est_ao + est_indirect )) "$hold_tests" gpu_tests
guarded ao "$est_ao" "$est_indirect" "$hold_ao" sweep ao
guarded indirect "$est_indirect" 0 "$hold_indirect" sweep indirect

# The summary: the device, each step, the tests' counts and the configurations recorded.
count_records() {  # FOLDER: statuses of the records.csv there and the repetitions measured
  [ -f "$1/records.csv" ] || { echo "no records"; return; }
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "status") c = i; next }
           c { n[$c]++ } END { s = ""; for (k in n) s = s (s ? ", " : "") n[k] " " k; printf "%s", (s ? s : "no records") }' "$1/records.csv"
  # A configuration's record is written once all its repetitions are measured; the journal
  # holds each repetition as it ends (what a stopped step leaves, and a rerun resumes from).
  echo " ($(grep -c '^{"repetition"' "$1/records.jsonl" 2>/dev/null || true) repetitions measured)"
}
test_counts() {  # XML: "tests T, failures F, skipped S"
  [ -f "$1" ] || { echo "not run"; return; }
  sed -n 's/.*<testsuites tests="\([0-9]*\)" failures="\([0-9]*\)" disabled="[0-9]*" errors="[0-9]*".*/tests \1, failures \2/p' "$1" | head -1
}
{
  echo "# GPU suite: $renderer"
  echo
  echo "$(date -u +%Y-%m-%dT%H:%M:%SZ), $([ "$dry_run" = 1 ] && echo 'dry run (tiny sizes)' || echo 'full sizes'), budget $budget s, took $(elapsed) s."
  echo "ldmbench: $ldmbench"
  [ -f "$data/MANIFEST.txt" ] && sed -n 's/^commit: /bundle commit: /p' "$data/MANIFEST.txt"
  echo
  echo '```'
  cat "$dir/info.txt"
  echo '```'
  echo
  echo "| step | status | estimated s | limit s | took s | note |"
  echo "| --- | --- | ---: | ---: | ---: | --- |"
  tail -n +2 "$dir/steps.tsv" | awk -F'\t' '{ printf "| %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6 }'
  echo
  echo "- tests: test_context $(test_counts "$dir/tests/test_context.xml"); test_structures $(test_counts "$dir/tests/test_structures.xml")"
  echo "- ao ($ao_configs configurations x $reps repetitions, $image): $(count_records "$dir/ao") (ao-sweep.json)"
  echo "- indirect ($indirect_configs configurations x $reps repetitions, $image): $(count_records "$dir/indirect") (indirect-sweep.json)"
  echo
  echo "Reports need Python (not in the bundle): at home, \`ldmbench report $device/ao $device/indirect --out $device/report\`."
} > "$dir/summary.md"
log "summary: $dir/summary.md"
cat "$dir/summary.md"
[ "$failed" = 1 ] && exit 1
[ "$some_failed" = 1 ] && exit 3
exit 0
