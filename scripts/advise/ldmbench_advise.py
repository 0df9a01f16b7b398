#!/usr/bin/env python3
"""ldmbench advise: the configuration of structure and parameters that meets a scene's
budgets with the least error (or the fastest within an error bound), found by an adaptive
search and verified at a normal run's precision. `ldmbench advise` checks the options and
runs this script; the search is ldmadvise/search.py, the strategy docs/guide/advise.md.

Writes into OUT: advise.json (the question, the identity a rerun must match), advise.jsonl
(the journal of every stage and pruning), stages/NN-STAGE/ (each stage's sweep file and run
folder; a rerun resumes them), verify/ (the recommendation's records at normal precision),
result.json and report/ (summary.md, front.png). Exit 0 with a recommendation, 1 when no
configuration meets the budgets (or an error), 2 for bad options or an empty space with
nothing written.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "report"))

from ldmadvise.cost import DEFAULT_SHARE, VerificationBudget  # noqa: E402
from ldmadvise.launch import LocalShards, SingleProcess, SlurmShards  # noqa: E402
from ldmadvise.measure import (CENSUS, LEVELS, VERIFY, VERIFY_SETTLE, VERIFY_UNCERTAIN, MeasureError, StageRunner,  # noqa: E402
                               measurement_of)
from ldmadvise.search import (MAYBE, YES, CensusPlan, Goal, Search, choose_best, primary_tied,  # noqa: E402
                              primary_value, rank_key)
from ldmadvise.space import (SpaceError, candidate_assignments, candidate_of, check_passes,  # noqa: E402
                             load_space, sweep_file)
from ldmadvise.report import counts_of, counts_sentence, fmt_bytes, write_report  # noqa: E402

EXIT_USAGE, EXIT_NONE = 2, 1
# scripts/slurm-sweep.sh beside this script's folder (the source tree), or installed beside it.
DEFAULT_SLURM_SCRIPT = next((p for p in (os.path.join(os.path.dirname(os.path.abspath(__file__)), d, "slurm-sweep.sh")
                                         for d in ("..", ".")) if os.path.isfile(p)), "")
QUESTION_FILE, JOURNAL_FILE, RESULT_FILE = "advise.json", "advise.jsonl", "result.json"


def fail(message, status=EXIT_USAGE):
    print(f"ldmbench advise: error: {message}", file=sys.stderr)
    sys.exit(status)


def parse_arguments(argv):
    p = argparse.ArgumentParser(prog="ldmbench_advise.py", description=__doc__.split("\n")[0])
    p.add_argument("--ldmbench", required=True, help="the ldmbench binary")
    p.add_argument("--axes", required=True, help="the axis registry (ldmbench axes --json)")
    p.add_argument("--scene", required=True)
    p.add_argument("--pass", dest="pass_name", default="ao",
                   help="the pass, or a comma list of AO methods (ao,gtao,hbao,rtao_gpu): the method is then an axis")
    p.add_argument("--budget-ms", type=float)
    p.add_argument("--budget-mib", type=float)
    p.add_argument("--max-error", type=float)
    p.add_argument("--min-mssim", type=float)
    p.add_argument("--structures", default="")
    p.add_argument("--space")
    p.add_argument("--image-size", default="128x128")
    p.add_argument("--out", required=True)
    p.add_argument("--cache-dir")
    p.add_argument("--reference-max-spp", type=int)
    p.add_argument("--levels", type=int, default=len(LEVELS), choices=range(1, len(LEVELS) + 1))
    p.add_argument("--cost-share", type=float, default=DEFAULT_SHARE,
                   help="the rounds of repeated verification run while advise's recorded time stays within "
                        "this share of an exhaustive sweep's (estimated; ldmadvise/cost.py)")
    p.add_argument("--overwrite", action="store_true")
    p.add_argument("--shards", type=int, default=1)
    p.add_argument("--launcher", default="local", choices=["local", "slurm"])
    p.add_argument("--slurm-script", default=DEFAULT_SLURM_SCRIPT)
    return p.parse_args(argv)


def check_budgets(a):
    for name, v in (("--budget-ms", a.budget_ms), ("--budget-mib", a.budget_mib), ("--max-error", a.max_error)):
        if v is not None and not (math.isfinite(v) and v > 0):
            fail(f"{name} {v}: expected a positive finite number")
    if a.min_mssim is not None and not (math.isfinite(a.min_mssim) and 0 < a.min_mssim <= 1):
        fail(f"--min-mssim {a.min_mssim}: expected a number in (0, 1]")
    if a.max_error is not None and a.min_mssim is not None:
        fail("--max-error and --min-mssim: give one error bound, not both")
    if a.shards < 1:
        fail(f"--shards {a.shards}: expected a positive count")
    if not (math.isfinite(a.cost_share) and a.cost_share > 0):
        fail(f"--cost-share {a.cost_share}: expected a positive finite share of an exhaustive sweep's time")
    if a.launcher == "slurm":
        if not a.slurm_script or not os.access(a.slurm_script, os.X_OK):
            fail(f"--launcher slurm: the job script {a.slurm_script or 'slurm-sweep.sh'} is not found or not "
                 "executable (--slurm-script names it)")
        if shutil.which("sbatch") is None or shutil.which("squeue") is None:
            fail("--launcher slurm: sbatch and squeue are not on PATH (Debian: slurm-client)")
    if a.budget_ms is None and a.budget_mib is None and a.max_error is None and a.min_mssim is None:
        fail("no budget: give --budget-ms, --budget-mib, --max-error or --min-mssim (else the answer "
             "is simply the largest N and R_LDM of the space)")


def goal_of(a):
    max_error = a.max_error if a.min_mssim is None else 1 - a.min_mssim
    return Goal(budget_ms=a.budget_ms, budget_bytes=int(a.budget_mib * 2**20) if a.budget_mib else None,
                max_error=max_error)


def dry_run_ids(ldmbench, spec):
    """The configuration ids `ldmbench sweep --dry-run` gives the space, in order; its
    refusal (exit 2, file and JSON path) as ours, with nothing written."""
    with tempfile.TemporaryDirectory(prefix="ldmbench-advise-") as tmp:
        path = os.path.join(tmp, "space-sweep.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(spec, f)
        r = subprocess.run([ldmbench, "sweep", path, "--dry-run"], capture_output=True, text=True)
    if r.returncode != 0:
        fail("the space does not make valid configurations: " + r.stderr.strip().replace(path, "space"))
    return [line.split("\t")[1] for line in r.stdout.splitlines() if "\t" in line]


def prepare_out(out, question, overwrite):
    """A new or empty folder, or one holding this same question (resumed)."""
    qpath = os.path.join(out, QUESTION_FILE)
    if os.path.isdir(out) and os.listdir(out):
        if not os.path.isfile(qpath):
            fail(f"--out: '{out}' is not empty and holds no advise ({QUESTION_FILE}); choose another folder")
        with open(qpath, encoding="utf-8") as f:
            earlier = json.load(f)
        if earlier != question:
            if not overwrite:
                fail(f"--out: '{out}' holds another advise (its {QUESTION_FILE} differs); choose another "
                     "folder, or --overwrite to replace it")
            shutil.rmtree(out)
        else:
            return True
    elif os.path.exists(out) and not os.path.isdir(out):
        fail(f"--out: '{out}' exists and is not a folder")
    os.makedirs(out, exist_ok=True)
    with open(qpath + ".tmp", "w", encoding="utf-8") as f:
        json.dump(question, f, indent=1, sort_keys=True)
    os.replace(qpath + ".tmp", qpath)
    return False


# Verification rounds after the first for the uncertain candidates it left unverified: while
# one of them is better on the criterion than every verified candidate surely within the
# budgets, the next two (in the search's order: medians within the budgets first, then best
# first) are verified the same way, at most VERIFY_MORE_ROUNDS rounds. Measured 2026-12-04 on
# the Cornell box: the first round's two uncertain candidates (error 0.0031) stayed across
# the budget line, and the unverified fourth (0.0079) was surely within in both exhaustive runs.
VERIFY_MORE_ROUNDS = 2

# Then one round for the verified candidates still across the budget line: the best of them
# (likely within first: its median within the budgets, then best on the criterion) that beats
# every verified candidate surely within is measured again with VERIFY_SETTLE's repetitions,
# twice the verification's. Three repetitions' interval is wide (the t factor for two degrees
# of freedom is 4.30); six narrow it to about half (2.57 / sqrt(6) against 4.30 / sqrt(3)),
# and the other run's share of the spread by sqrt(2), which places most such candidates on
# one side of the budget. Measured 2026-12-05 on the Cornell box at 6.5 ms: PPFLA N 8 R_LDM 64
# verified at 5.23 ms [4.11, 6.66] with error 0.0079, against the answer's 0.0098; one
# exhaustive run measured it surely within and refuted the answer. Two candidates: with one,
# the round settled PPFLA N 16 R_LDM 32 (error 0.0031, median 6.17 ms, within) on the same
# question later that day and found it still across, while N 8 R_LDM 64 (0.0079, 5.03 ms
# [3.75, 6.74]), surely within in both exhaustive runs, went unsettled and the answer fell to
# an error of 0.0199. The round's six processes measure both.
SETTLE_KEYS = 2


def beats_best_within(goal, verified):
    """Whether a measurement is better on the criterion, beyond the bands, than the best
    verified candidate surely within the budgets (true when there is none)."""
    within = [k for k, m in verified.items() if m.status == "ok" and goal.verdict(m) == YES]
    best = choose_best(goal, within, lambda k: verified[k]) if within else None

    def better(m):
        return best is None or (primary_value(goal, m) < primary_value(goal, verified[best])
                                and not primary_tied(goal, m, verified[best]))
    return better


def verify_again(runner, search, keys, precision, stage, verified, vsource):
    """Measures `keys` at `precision` in a stage of their own; their new measurements replace
    the verified ones, and their records become the ones an answer would report."""
    more, folder, rows, records = runner.run_stage(keys, precision, stage)
    for k, m in more.items():
        m.level = len(LEVELS)
        search.states[k].measurement = m
        search.states[k].history.append(m)
        verified[k] = m
        vsource[k] = (folder, rows, records)


def affordable(runner, budget, keys, precision, stage):
    """Whether the round fits the verification budget (ldmadvise/cost.py); a round left out is
    journaled and kept for the answer."""
    why = budget.refusal(runner.recorded_s(), keys, precision.get("repetitions", 1))
    if why:
        budget.skip(stage, keys, why)
        runner.log({"event": "skipped", "stage": stage, "keys": list(keys), "why": why})
    return not why


def verify_more_uncertain(runner, search, goal, outcome, verified, vsource, stage, budget):
    pending = [k for k in outcome.uncertain if k not in verified]
    for round_number in range(1, VERIFY_MORE_ROUNDS + 1):
        better = beats_best_within(goal, verified)
        batch = [k for k in pending if better(search.states[k].measurement)][:2]
        round_stage = f"{stage}-uncertain-{round_number}"
        if not batch or not affordable(runner, budget, batch, VERIFY_UNCERTAIN, round_stage):
            return
        verify_again(runner, search, batch, VERIFY_UNCERTAIN, round_stage, verified, vsource)
        budget.observe(runner.costs[-1])
        pending = [k for k in pending if k not in batch]


def settle_budget_line(runner, search, goal, verified, vsource, stage, budget):
    better = beats_best_within(goal, verified)
    across = [k for k, m in verified.items() if m.status == "ok" and goal.verdict(m) == MAYBE and better(m)]
    # Likely within first (best first); then the least over a budget, the likeliest to be
    # found within.
    across.sort(key=lambda k: (0, rank_key(goal, verified[k])) if goal.likely_within(verified[k])
                else (1, (goal.overshoot(verified[k]),)))
    if across and affordable(runner, budget, across[:SETTLE_KEYS], VERIFY_SETTLE, f"{stage}-settle"):
        verify_again(runner, search, across[:SETTLE_KEYS], VERIFY_SETTLE, f"{stage}-settle", verified, vsource)


def skipped_rounds_line(budget):
    rounds = "; ".join(f"{r['stage']} ({', '.join(r['keys'])})" for r in budget.skipped)
    return (f"- not measured again, the verification budget being spent (--cost-share {budget.share:g}; "
            f"{budget.skipped[0]['why']}): {rounds}. The same command with a larger --cost-share measures "
            "them, keeping every stage done.")


def freeze_calibration(ldmbench, launcher, log):
    """One run-to-run spread for every stage: the cache entry of this machine, probed first
    where `--calibration auto` would probe it (missing, older than a day, or taken at
    another load), then handed to every stage (LDM_CALIBRATION=FILE). Without it each stage
    decides for itself: on the Cornell box a stage probed again in the middle of an advise
    (5 s of its 18; 2026-12-05), because the advise's own stages had moved the load, and
    stages judged by different spreads compare intervals of different widths. A user's
    LDM_CALIBRATION (skip, or a file) is kept; Slurm stages run on other machines, whose
    spread is their own."""
    if os.environ.get("LDM_CALIBRATION") or launcher == "slurm":
        return
    def show():
        out = subprocess.run([ldmbench, "calibrate", "--show", "--json"], capture_output=True, text=True)
        if out.returncode != 0:
            raise MeasureError(f"`{ldmbench} calibrate --show --json` failed:\n{out.stdout}{out.stderr}")
        return json.loads(out.stdout[out.stdout.index("{"):])
    state = show()
    stale = state["stale"] if not state["current"] else ""
    if stale:
        out = subprocess.run([ldmbench, "calibrate"], capture_output=True, text=True)
        if out.returncode != 0:
            raise MeasureError(f"`{ldmbench} calibrate` failed:\n{out.stdout}{out.stderr}")
        state = show()
    os.environ["LDM_CALIBRATION"] = state["file"]
    log({"event": "calibration", "file": state["file"], "spread": state.get("spread"),
         "probed_because": stale or None})


def main(argv):
    a = parse_arguments(argv)
    check_budgets(a)
    with open(a.axes, encoding="utf-8") as f:
        registry = json.load(f)
    by_key = {axis["name"]: axis for axis in registry["axes"]}
    names = set(by_key)
    structures_known = by_key["structures"]["choices"]
    passes_known = by_key["passes"]["choices"]
    wanted = [s for s in a.structures.split(",") if s]
    for s in wanted:
        if s not in structures_known:
            fail(f"--structures: unknown structure {s!r} (known: {', '.join(structures_known)})")
    try:
        passes = check_passes([p for p in a.pass_name.split(",") if p], passes_known)
        axes = load_space(a.space, passes, wanted, structures_known, passes_known)
        for key in axes:
            if ":" in key and names and key not in names:
                raise SpaceError(f"{a.space or 'the default space'}: axes.{key}: not a parameter "
                                 "(`ldmbench axes` lists them)")
        assignments = candidate_assignments(axes, passes)
    except SpaceError as e:
        fail(str(e))
    if not assignments:
        fail(f"{a.space or 'the default space'}: the space is empty")
    question = {"scene": a.scene, "pass": a.pass_name, "image_size": a.image_size,
                "reference_max_spp": a.reference_max_spp}
    ids = dry_run_ids(a.ldmbench, sweep_file(question, assignments, LEVELS[0], "advise space"))
    if len(ids) != len(assignments) or len(set(ids)) != len(ids):
        fail(f"the space's {len(assignments)} assignments make {len(set(ids))} distinct configurations; "
             "remove the axes that do not change the configuration")
    by_id = dict(zip(ids, assignments))
    defaults = {"views": 32, "r_ldm": 128}
    candidates = [candidate_of(k, by_id[k], defaults) for k in ids]
    goal = goal_of(a)
    metric = "mssim" if a.min_mssim is not None else "mse"
    identity = {"question": question, "goal": {"budget_ms": a.budget_ms, "budget_mib": a.budget_mib,
                                                "max_error": a.max_error, "min_mssim": a.min_mssim},
                "space": axes, "levels": a.levels, "configurations": ids}
    resumed = prepare_out(a.out, identity, a.overwrite)

    journal_path = os.path.join(a.out, JOURNAL_FILE)

    def log(event):
        event = dict(event, t=round(time.time(), 3))
        with open(journal_path, "a", encoding="utf-8") as f:
            f.write(json.dumps(event) + "\n")

    earlier_events = read_journal(journal_path)
    log({"event": "resumed" if resumed else "started", "configurations": len(ids),
         "launcher": a.launcher, "shards": a.shards})
    start = time.monotonic()
    try:
        freeze_calibration(a.ldmbench, a.launcher, log)
    except MeasureError as e:
        fail(str(e), EXIT_NONE)
    runner = StageRunner(launcher_of(a, earlier_events), a.out, question, by_id, metric, log)

    def measure(cands, level, stage):
        results, _, _, _ = runner.run_stage([c.key for c in cands], LEVELS[level], stage)
        return results

    def census(cands):
        # The memory plan of every candidate: the fragments counted, each structure's storage
        # planned by its own prepare(), nothing built or timed (ldmbench sweep --memory-plan).
        rows = runner.plan_stage([c.key for c in cands])
        plan = CensusPlan()
        for c in cands:
            row = rows[c.key]
            if row.get("status") == "refused":
                plan.refused[c.key] = row.get("status_detail") or "refused"
                continue
            depth, planned = number_of(row, "max_depth_complexity"), number_of(row, "bytes_allocated")
            if math.isfinite(depth):
                plan.depths[(c.views, c.r_ldm)] = int(depth)
            if math.isfinite(planned):
                plan.memory[c.key] = int(planned)
        return plan

    search = Search(candidates, goal, a.levels, measure, log, census)
    budget = VerificationBudget(a.cost_share, len(ids))
    try:
        outcome = search.run()
        verified, attempt = {}, 1
        while outcome.recommended:
            # Verify; a recommendation the normal-precision run finds outside the budgets is
            # dropped (what it had beaten comes back) and the race resumes at its top level.
            # Those across the budget line (better, but not surely within) are measured with
            # them, with repetitions, before the recommendation drops them (at most two).
            uncertain = outcome.uncertain[:2]
            keys = [outcome.recommended] + outcome.ties[:1] + uncertain
            stage = "verify" if attempt == 1 else f"verify-{attempt}"
            verified, vfolder, vrows, vrecords = runner.run_stage(keys, VERIFY_UNCERTAIN if uncertain else VERIFY,
                                                                  stage)
            vsource = {k: (vfolder, vrows, vrecords) for k in keys}
            for k, m in verified.items():  # the report shows each at its last precision
                m.level = len(LEVELS)
                search.states[k].measurement = m
                search.states[k].history.append(m)
            if any(m.status == "ok" and goal.verdict(m) != "no" for m in verified.values()):
                budget.learn(runner.costs[-1])
                verify_more_uncertain(runner, search, goal, outcome, verified, vsource, stage, budget)
                settle_budget_line(runner, search, goal, verified, vsource, stage, budget)
                break
            for k in keys:
                search.recheck(k, stage)
            outcome = search.run(level=a.levels - 1)
            attempt += 1
    except MeasureError as e:
        fail(str(e), EXIT_NONE)
    elapsed = time.monotonic() - start

    answer, recommended, rec_row = [], None, None
    if outcome.recommended:
        # The verified measurement decides: the best verified one within the budgets.
        ok = [k for k, m in verified.items() if m.status == "ok" and goal.verdict(m) == YES]
        maybe = [k for k, m in verified.items() if m.status == "ok" and goal.verdict(m) != "no"]
        pool = ok or maybe
        if pool:
            recommended = choose_best(goal, pool, lambda k: verified[k])
            vfolder, vrows, vrecords = vsource[recommended]
            rec_row = vrows[recommended]
    # Ties as verified: those measured at normal precision that the bands cannot tell from
    # the recommendation; the search's other ties (at its own precision) beside them.
    verified_ties = [k for k, m in verified.items() if recommended and k != recommended and m.status == "ok"
                     and goal.verdict(m) != "no" and primary_tied(goal, m, verified[recommended])]
    # Across the budget line as verified: better than the recommendation (or tied) on the
    # criterion, but not surely within a budget: named, never dropped silently.
    across = [k for k, m in verified.items() if recommended and k != recommended and m.status == "ok"
              and goal.verdict(m) == "maybe" and (primary_tied(goal, m, verified[recommended]) or
                                                   primary_value(goal, m) < primary_value(goal, verified[recommended]))]
    result = {"recommended": recommended, "search_recommended": outcome.recommended,
              "ties": verified_ties, "across_budget_line": across,
              "search_uncertain_unverified": [k for k in outcome.uncertain if k not in verified],
              "search_ties_unverified": [k for k in outcome.ties if k not in verified],
              "why_stopped": outcome.why, "configurations": len(ids),
              "plan_differs": search.plan_differences,
              "wall_s_this_call": round(elapsed, 2), "resumed": resumed,
              "verification_budget": budget.summary(runner.recorded_s()),
              "pruned": {k: s.pruned for k, s in search.states.items() if s.pruned}}
    # Every count the outputs say, from the stages' costs alone (ldmadvise/report.py counts_of):
    # the console, summary.md and result.json say the same numbers.
    counts = counts_of(runner.costs, len(ids))
    result.update(counts=counts, measured=counts["measured"], planned=counts["planned"],
                  wall_s_recorded=counts["wall_s_recorded"])
    if recommended:
        m = verified[recommended]
        surely = goal.verdict(m) == YES
        vf = number_of(rec_row, "wall_seconds")
        ref_noise = number_of(rec_row, "ref_noise_mse")
        result["verified"] = {"folder": vfolder, "records": vrecords, "frame_ms": m.time, "frame_ms_interval": [m.time_low, m.time_high],
                              "error": m.error, "error_band": m.error_band, "metric": metric,
                              "mse_over_noise": number_of(rec_row, "mse_over_noise"),
                              "bytes_allocated": m.memory, "within_budgets_surely": surely,
                              "wall_s": vf}
        answer = [f"Recommended: **{recommended}** ({'surely within' if surely else 'within, but not surely within,'} "
                  f"the budgets at a normal run's precision; record in {os.path.relpath(vrecords, a.out)}).",
                  "",
                  f"- frame time {m.time:.4g} ms, 95 % interval [{m.time_low:.4g}, {m.time_high:.4g}]"
                  + (f" (budget {goal.budget_ms} ms)" if goal.budget_ms else ""),
                  f"- error {metric} {m.error:.4g}, the reference's noise {m.error_band:.2g} "
                  f"({number_of(rec_row, 'mse_over_noise'):.4g} x noise in MSE)"
                  + (f" (bound {goal.max_error})" if goal.max_error is not None else ""),
                  f"- memory {m.memory} bytes ({fmt_bytes(m.memory)}), exact"
                  + (f" (budget {a.budget_mib} MiB)" if a.budget_mib else ""),
                  "- tied with it at normal precision (not separable within the bands): "
                  + (", ".join(result["ties"]) or "none")
                  + (f"; tied at the search's precision, not verified: {', '.join(result['search_ties_unverified'])}"
                     if result["search_ties_unverified"] else ""),
                  "- across the budget line (better on " + goal.minimize + ", but its interval straddles a budget, "
                  "so not surely within it): "
                  + (", ".join(f"{k} ({verified[k].time:.4g} ms [{verified[k].time_low:.4g}, {verified[k].time_high:.4g}])"
                               for k in across) or "none")
                  + (f"; at the search's precision, not verified: {', '.join(result['search_uncertain_unverified'])}"
                     if result["search_uncertain_unverified"] else ""),
                  f"- surer: `--repetitions 3` on the verify run narrows the time interval for about 3 x "
                  f"{vf:.3g} s; halving the error band needs a reference with twice the samples "
                  f"(noise {ref_noise:.2g} now)."]
        if budget.skipped:
            answer.insert(-1, skipped_rounds_line(budget))
    else:
        answer = ["No configuration of the space meets the budgets "
                  f"({outcome.why}); see the pruned table for each one's reason."]
    result["answer_lines"] = answer
    title = f"ldmbench advise: {a.scene}, {a.pass_name}" + \
            (f", {a.budget_ms} ms" if a.budget_ms else "") + (f", {a.budget_mib} MiB" if a.budget_mib else "") + \
            (f", error <= {goal.max_error:g}" if goal.max_error is not None else "")
    folder = write_report(a.out, result, search, goal, metric, runner.costs, title)
    with open(os.path.join(a.out, RESULT_FILE + ".tmp"), "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1, default=str)
    os.replace(os.path.join(a.out, RESULT_FILE + ".tmp"), os.path.join(a.out, RESULT_FILE))
    log({"event": "finished", "recommended": recommended, "wall_s": round(elapsed, 2)})
    print("\n".join(answer))
    print(f"{counts_sentence(counts)}; report: {folder}/summary.md")
    return 0 if recommended else EXIT_NONE


def read_journal(path):
    """The events of earlier calls of this advise (a Slurm stage still running is reattached)."""
    events = []
    if os.path.isfile(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                try:
                    events.append(json.loads(line))
                except json.JSONDecodeError:
                    pass  # a line cut short by a kill
    return events


def launcher_of(a, earlier_events):
    if a.launcher == "slurm":
        return SlurmShards(a.ldmbench, a.cache_dir, a.shards, a.slurm_script, earlier_events,
                           poll_s=float(os.environ.get("LDM_ADVISE_POLL_S", "2")))
    if a.shards > 1:
        return LocalShards(a.ldmbench, a.cache_dir, a.shards)
    return SingleProcess(a.ldmbench, a.cache_dir)


def number_of(row, column):
    try:
        return float(row.get(column, "nan"))
    except (TypeError, ValueError):
        return math.nan


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
