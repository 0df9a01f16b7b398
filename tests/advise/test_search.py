#!/usr/bin/env python3
"""The advise search (scripts/advise/ldmadvise/search.py) on synthetic cost and error
models whose optimum is known: the recommendation, the ties, infeasible budgets, noisy
measurements, and that the search measures less than the whole space. Run by
tests/advise/advise_test.cpp (ctest advise.SearchOnSyntheticModels)."""
import itertools
import os
import random
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "advise"))

from ldmadvise.report import counts_of, counts_sentence, write_report  # noqa: E402
from ldmadvise.search import Candidate, CensusPlan, Goal, Measurement, Search, pareto_front  # noqa: E402
from ldmadvise.space import (SpaceError, candidate_assignments, check_passes, group_of,  # noqa: E402
                             load_space, sweep_file)

VIEWS, RES = [4, 8, 16, 32, 64], [32, 64, 128, 256]
SPEED = {"fast": 1.0, "mid": 1.5, "slow": 2.5}   # frame time per unit of work
MEMORY = {"fast": 40, "mid": 16, "slow": 8}       # bytes per LDM pixel


def space(structures=("fast", "mid", "slow"), ks=()):
    out = []
    for s in structures:
        for n, r in itertools.product(VIEWS, RES):
            out.append(Candidate(f"{s}-n{n}-r{r}", s, n, r))
    for k in ks:
        for n, r in itertools.product(VIEWS, RES):
            out.append(Candidate(f"fla{k}-n{n}-r{r}", f"fla{k}", n, r, k=k))
    return out


def true_time(c):
    speed = SPEED.get(c.group, 1.2)
    return speed * (c.views * 0.5 + c.views * (c.r_ldm / 64) ** 2 * 0.25)


def true_error(c):
    return 1.0 / c.views + 3.3 / c.r_ldm  # no two geometries err alike


def true_memory(c):
    per_pixel = MEMORY.get(c.group, 4 * (c.k or 1))
    return c.views * c.r_ldm ** 2 * per_pixel


class Model:
    """measure(): the true values with noise that shrinks with the level (3 levels), the
    time interval and error band covering the truth; counts what it measures."""

    def __init__(self, noise=0.0, seed=1, depth=6, error_of=true_error):
        self.noise, self.rng, self.depth, self.error_of = noise, random.Random(seed), depth, error_of
        self.measured, self.calls = [], 0

    def __call__(self, candidates, level, stage):
        self.calls += 1
        out = {}
        for c in candidates:
            self.measured.append((c.key, level))
            scale = self.noise / (2 ** level)
            t = true_time(c) * (1 + self.rng.uniform(-scale, scale))
            half = true_time(c) * scale * 1.05 + 1e-9
            e = self.error_of(c)
            band = e * scale + 1e-12
            e_obs = e + self.rng.uniform(-band, band) * 0.9
            status = "lossy" if c.k is not None and c.k < self.depth else "ok"
            out[c.key] = Measurement(time=t, time_low=t - half, time_high=t + half, error=e_obs,
                                     error_band=band, memory=true_memory(c), status=status,
                                     max_depth=self.depth)
        return out


def exhaustive(cands, goal):
    """The truth: the least error (or time) among the configurations within the budgets."""
    feasible = [c for c in cands if (goal.budget_ms is None or true_time(c) <= goal.budget_ms)
                and (goal.budget_bytes is None or true_memory(c) <= goal.budget_bytes)
                and (goal.max_error is None or true_error(c) <= goal.max_error)
                and not (c.k is not None and c.k < 6)]
    if not feasible:
        return None
    key = (lambda c: (true_time(c), true_error(c))) if goal.minimize == "time" else \
        (lambda c: (true_error(c), true_time(c)))
    return min(feasible, key=key)


class ExactModels(unittest.TestCase):
    def run_search(self, goal, cands=None, model=None, levels=3):
        cands = cands or space()
        model = model or Model()
        events = []
        outcome = Search(cands, goal, levels, model, events.append).run()
        return outcome, model, events

    def test_least_error_within_time_budget(self):
        goal = Goal(budget_ms=40)
        outcome, model, _ = self.run_search(goal)
        truth = exhaustive(space(), goal)
        self.assertEqual(outcome.recommended, truth.key)
        # the structures erring alike at that geometry (and within the budget) are its ties
        same = {c.key for c in space() if (c.views, c.r_ldm) == (truth.views, truth.r_ldm)
                and true_time(c) <= goal.budget_ms} - {truth.key}
        self.assertEqual(set(outcome.ties), same)
        # cheap first: far fewer measurements than the space
        self.assertLess(len({k for k, _ in model.measured}), len(space()) // 2)

    def test_fastest_within_error_bound(self):
        goal = Goal(max_error=0.2)
        outcome, model, _ = self.run_search(goal)
        self.assertEqual(outcome.recommended, exhaustive(space(), goal).key)

    def test_memory_budget(self):
        goal = Goal(budget_ms=200, budget_bytes=8 * 64 * 64 * 16)
        outcome, _, events = self.run_search(goal)
        truth = exhaustive(space(), goal)
        self.assertEqual(outcome.recommended, truth.key)
        self.assertTrue(any(e.get("why", "").startswith("memory") for e in events))

    def test_infeasible_budget_recommends_nothing(self):
        goal = Goal(budget_ms=0.01)
        outcome, _, events = self.run_search(goal)
        self.assertIsNone(outcome.recommended)
        self.assertEqual(outcome.ties, [])
        pruned = [e for e in events if e["event"] == "pruned"]
        self.assertEqual(len(pruned), len(space()))  # every candidate pruned, each with a reason
        self.assertTrue(all(e["why"] for e in pruned))

    def test_lossy_fixed_arrays_pruned_by_census_or_status(self):
        cands = space(structures=("slow",), ks=(2, 8))
        goal = Goal(budget_ms=60)
        outcome, model, events = self.run_search(goal, cands)
        self.assertEqual(outcome.recommended, exhaustive(cands, goal).key)
        why = {e["config_id"]: e["why"] for e in events if e["event"] == "pruned"}
        for c in cands:
            if c.k == 2:
                self.assertIn("lossy", why[c.key])
        census = [k for k, w in why.items() if "census" in w]
        self.assertTrue(census, "the census prunes some short arrays without measuring them")
        measured = {k for k, _ in model.measured}
        self.assertTrue(all(k not in measured for k in census))

    def test_census_stage_prunes_short_arrays_before_any_measurement(self):
        cands = space(structures=("slow",), ks=(2, 8))
        asked = []

        def census(candidates):
            asked.extend(candidates)
            return CensusPlan(depths={(c.views, c.r_ldm): 6 for c in candidates})

        model, events = Model(), []
        outcome = Search(cands, Goal(budget_ms=60), 3, model, events.append, census).run()
        self.assertEqual(sorted(c.key for c in asked), sorted(c.key for c in cands))
        measured = {k for k, _ in model.measured}
        self.assertFalse([c.key for c in cands if c.k == 2 and c.key in measured])
        self.assertEqual(outcome.recommended, exhaustive(cands, Goal(budget_ms=60)).key)

    def test_census_memory_plan_prunes_over_budget_before_any_measurement(self):
        # The plan's exact bytes drop every configuration over the budget unmeasured (the
        # lattice rule alone would have measured some); a refused one is dropped with its reason.
        cands = space()
        goal = Goal(budget_ms=200, budget_bytes=8 * 64 * 64 * 16)
        refused = cands[0].key

        def census(candidates):
            return CensusPlan(memory={c.key: true_memory(c) for c in candidates},
                              refused={refused: "a buffer over the storage block"})

        model, events = Model(), []
        outcome = Search(cands, goal, 3, model, events.append, census).run()
        over = {c.key for c in cands if true_memory(c) > goal.budget_bytes}
        self.assertTrue(over)
        measured = {k for k, _ in model.measured}
        self.assertFalse(over & measured, "measured a configuration the plan puts over the budget")
        self.assertNotIn(refused, measured)
        why = {e["config_id"]: e["why"] for e in events if e["event"] == "pruned"}
        self.assertTrue(all(why[k].startswith("memory (census)") for k in over if k != refused))
        self.assertTrue(why[refused].startswith("refused (census)"))
        self.assertEqual(outcome.recommended, exhaustive([c for c in cands if c.key != refused], goal).key)

    def test_ties_are_shown_as_ties(self):
        # two structures with the same time and error: the answer names both
        cands = space(structures=("fast",)) + [Candidate(c.key.replace("fast", "twin"), "twin", c.views, c.r_ldm)
                                              for c in space(structures=("fast",))]
        SPEED["twin"], MEMORY["twin"] = SPEED["fast"], MEMORY["fast"]
        try:
            goal = Goal(budget_ms=40)
            outcome, _, _ = self.run_search(goal, cands)
        finally:
            del SPEED["twin"], MEMORY["twin"]
        truth = exhaustive(space(structures=("fast",)), goal).key
        self.assertEqual({outcome.recommended} | set(outcome.ties), {truth, truth.replace("fast", "twin")})

    def test_empty_space_refused(self):
        with self.assertRaises(ValueError):
            Search([], Goal(budget_ms=1), 3, Model())


class RevivedCandidatesAreMeasuredAgain(unittest.TestCase):
    def test_a_revived_candidate_is_remeasured_before_it_is_compared(self):
        # A was dominated by C at the brief level; C turns out over the time budget at level 1,
        # so A comes back. A's brief error is biased up by its noisier reference (beyond its
        # band): compared as it is with B's level-1 error, A would be "beaten". It must be
        # measured at level 1 first, where it ties B's error and is faster.
        a = Candidate("s-n8-r64", "s", 8, 64)
        b = Candidate("w-n8-r64", "w", 8, 64)
        c = Candidate("s-n8-r128", "s", 8, 128)
        truth = {a.key: (15.0, 0.10), b.key: (24.0, 0.10), c.key: (30.0, 0.08)}
        asked = []

        def measure(cands, level, stage):
            out = {}
            for x in cands:
                asked.append((x.key, level))
                t, e = truth[x.key]
                out[x.key] = Measurement(time=t, time_low=t - 0.2, time_high=t + 0.2,
                                         error=e + (0.02 if level == 0 else 0.0), error_band=0.001, memory=1)
            return out

        search = Search([a, b, c], Goal(budget_ms=28), 2, measure)
        for key, level in ((a.key, 0), (b.key, 1), (c.key, 1)):
            m = measure([search.states[key].candidate], level, "setup")[key]
            m.level = level
            search.states[key].measurement = m
        search.states[a.key].pruned, search.states[a.key].pruned_by = "dominated (lattice)", c.key
        asked.clear()
        outcome = search.race(level=1)
        self.assertIn((a.key, 1), asked)
        self.assertEqual(outcome.recommended, a.key)
        self.assertEqual(outcome.ties, [b.key])


class OptimisticBriefMeasurement(unittest.TestCase):
    def test_a_recommendation_failing_verification_revives_what_it_beat(self):
        """The brief measurement of the true optimum's better neighbour is optimistic (within
        the budget); at a normal run's precision it is over. What it beat or dominated comes
        back, and the search ends at the true optimum."""
        goal = Goal(budget_ms=40)
        cands = space(structures=("fast",))
        truth = exhaustive(cands, goal)
        liar = "fast-n32-r128"  # truly 1.0 * (16 + 32 * 4 * 0.25) = 48 ms > 40

        class Liar(Model):
            def __call__(self, candidates, level, stage):
                out = super().__call__(candidates, level, stage)
                if liar in out and level < 2:
                    m = out[liar]
                    m.time, m.time_low, m.time_high = 30.0, 29.0, 31.0
                return out

        model, events = Liar(), []
        search = Search(cands, goal, 3, model, events.append)
        outcome = search.run()
        self.assertEqual(outcome.recommended, liar)  # what the brief measurements say
        # verification (as ldmbench_advise.py does it): the normal-precision measurement
        search.states[liar].measurement = model([search.states[liar].candidate], 2, "verify")[liar]
        search.states[liar].measurement.level = 3
        self.assertFalse(search.recheck(liar, "verify"))
        outcome = search.run(level=2)
        self.assertEqual(outcome.recommended, truth.key)
        self.assertTrue(any(e["event"] == "revived" for e in events))


def same_at_every_level(values):
    """A measure that finds, at every level, each candidate's group's (time, its interval's low
    and high, error) from values, with an error band of 0.001 and 100 bytes."""
    def measure(cands, level, stage):
        return {x.key: Measurement(*values[x.group], 0.001, 100) for x in cands}
    return measure


class UncertainAtEveryLevel(unittest.TestCase):
    def test_none_surely_within_sends_the_best_that_may_be_to_verification(self):
        """Both candidates' intervals straddle the budget at every level: the search does
        not give up; the one with less error goes to verification, which decides."""
        b, c = Candidate("b-n8-r64", "b", 8, 64), Candidate("c-n8-r64", "c", 8, 64)
        measure = same_at_every_level({"b": (20, 15, 25, 0.2), "c": (21, 15, 25, 0.3)})
        outcome = Search([b, c], Goal(budget_ms=22), 2, measure).run()
        self.assertEqual(outcome.recommended, b.key)
        self.assertIn("verification", outcome.why)


    def test_a_better_candidate_straddling_the_budget_is_named_across_the_budget_line(self):
        """a is surely within the budget; b has less error, but its interval straddles the
        budget at every level: a is recommended and b named as uncertain (it goes to the
        repeated verification), never dropped silently; c, worse and straddling, is not."""
        a, b, c = (Candidate("a-n8-r64", "a", 8, 64), Candidate("b-n8-r64", "b", 8, 64),
                   Candidate("c-n8-r64", "c", 8, 64))
        measure = same_at_every_level({"a": (10, 9, 11, 0.3), "b": (19, 15, 25, 0.1), "c": (20, 16, 24, 0.5)})
        outcome = Search([a, b, c], Goal(budget_ms=22), 2, measure).run()
        self.assertEqual(outcome.recommended, a.key)
        self.assertEqual(outcome.uncertain, [b.key])

    def test_uncertain_candidates_whose_median_is_within_go_to_verification_first(self):
        """b and d are better than a and both straddle the budget; b has the least error but
        its median is over the budget, d's is under it: d is listed first, so the limited
        verification measures the one likely to be found within before the one likely not."""
        a, b, d = (Candidate("a-n8-r64", "a", 8, 64), Candidate("b-n8-r64", "b", 8, 64),
                   Candidate("d-n8-r64", "d", 8, 64))
        measure = same_at_every_level({"a": (10, 9, 11, 0.3), "b": (23, 18, 29, 0.1), "d": (20, 16, 24, 0.2)})
        outcome = Search([a, b, d], Goal(budget_ms=22), 2, measure).run()
        self.assertEqual(outcome.recommended, a.key)
        self.assertEqual(outcome.uncertain, [d.key, b.key])


class NoisyModels(unittest.TestCase):
    def test_noisy_measurements_find_a_tied_optimum(self):
        """With noise, the recommendation is the true optimum or tied with it within the
        final bands, and surely within the budget; over several seeds."""
        goal = Goal(budget_ms=40)
        truth = exhaustive(space(), goal)
        for seed in range(8):
            model = Model(noise=0.3, seed=seed)
            outcome = Search(space(), goal, 3, model).run()
            self.assertIsNotNone(outcome.recommended, seed)
            rec = next(c for c in space() if c.key == outcome.recommended)
            self.assertLessEqual(true_time(rec), goal.budget_ms, seed)
            # its error is the optimum's within the last level's band (noise 0.3 / 4)
            self.assertLessEqual(true_error(rec), true_error(truth) * (1 + 2 * 0.3 / 4) + 1e-12, seed)

    def test_more_precision_only_near_the_front(self):
        goal = Goal(budget_ms=40)
        model = Model(noise=0.3, seed=3)
        Search(space(), goal, 3, model).run()
        level0 = {k for k, lv in model.measured if lv == 0}
        level2 = {k for k, lv in model.measured if lv == 2}
        self.assertLess(len(level2), len(level0))


class Front(unittest.TestCase):
    def test_pareto_front_with_ties(self):
        m = lambda t, e: Measurement(t, t - 0.5, t + 0.5, e, 0.01, 1)  # noqa: E731
        ms = {"a": m(1, 1.0), "b": m(1.2, 1.0), "c": m(5, 0.5), "d": m(6, 0.9), "e": m(9, 0.1)}
        # a and b tie in both; d is beaten by c in both
        self.assertEqual(pareto_front(Goal(budget_ms=10), ms), ["a", "b", "c", "e"])


class Space(unittest.TestCase):
    def test_parameters_apply_to_their_owner_only(self):
        axes = {"structures": ["psppsll", "ppfla"], "views": [8, 16], "r_ldm": 64, "ppfla:k": [4, 8]}
        assignments = candidate_assignments(axes, "ao")
        self.assertEqual(len(assignments), 2 + 4)
        self.assertTrue(all("ppfla:k" not in a for a in assignments if a["structures"] == "psppsll"))
        self.assertNotEqual(group_of(assignments[2]), group_of(assignments[3]))  # k=4 vs k=8 lattices

    def test_the_method_is_an_axis_with_each_peer_on_its_own_parameters(self):
        passes = ["ao", "gtao", "rtao_gpu"]
        registry = ["ao", "hbao", "gtao", "rtao", "rtao_gpu", "indirect"]
        axes = load_space(None, passes, [], ["psppsll", "ppfla", "psppfla"], registry)
        self.assertIn("gtao:slices", axes)   # the peers' default knobs join the LDM pass's space
        self.assertIn("rtao_gpu:spp", axes)
        assignments = candidate_assignments(axes, passes)
        peers = [a for a in assignments if a["passes"] != "ao"]
        self.assertEqual(len([a for a in peers if a["passes"] == "gtao"]),
                         len(axes["gtao:slices"]) * len(axes["gtao:steps"]))
        self.assertEqual(len([a for a in peers if a["passes"] == "rtao_gpu"]), len(axes["rtao_gpu:spp"]))
        for a in peers:  # no structure, N, R_LDM, nor another owner's parameter
            self.assertFalse({"structures", "views", "r_ldm"} & set(a), a)
            self.assertTrue(all(k.split(":")[0] == a["passes"] for k in a if ":" in k), a)
        ldm = [a for a in assignments if a["passes"] == "ao"]
        self.assertTrue(ldm and all("gtao:slices" not in a and "structures" in a for a in ldm))
        # Each peer configuration its own lattice (its parameters differ), apart from the LDM ones.
        groups = {group_of(a) for a in peers}
        self.assertEqual(len(groups), len(peers))
        self.assertFalse(groups & {group_of(a) for a in ldm})
        spec = sweep_file({"scene": "cornell", "pass": ",".join(passes), "image_size": "32x32"}, assignments,
                          {"name": "brief", "frames": 3, "warmup": 1, "target": 0}, "t")
        self.assertEqual(spec["axes"]["passes"], "ao")
        self.assertEqual(sum(1 for b in spec["include"] if b["passes"] == "gtao"), 9)

    def test_passes_are_checked(self):
        registry = ["ao", "hbao", "gtao", "rtao", "rtao_gpu", "indirect"]
        self.assertEqual(check_passes(["ao", "gtao"], registry), ["ao", "gtao"])
        with self.assertRaisesRegex(SpaceError, r"unknown passes 'gtoa', 'hboa'"):
            check_passes(["ao", "gtoa", "hboa"], registry)
        with self.assertRaisesRegex(SpaceError, "only the AO passes"):
            check_passes(["ao", "indirect"], registry)
        with self.assertRaisesRegex(SpaceError, "twice"):
            check_passes(["ao", "ao"], registry)

    def test_question_axes_refused(self):
        import json
        import tempfile
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            json.dump({"axes": {"image_size": "64x64"}}, f)
        try:
            with self.assertRaisesRegex(SpaceError, "axes.image_size: fixed by the question"):
                load_space(f.name, "ao", [], ["psppsll"], ["ao"])
        finally:
            os.unlink(f.name)

    def test_sweep_file_measures_exactly_the_subset(self):
        q = {"scene": "cornell", "pass": "ao", "image_size": "32x32"}
        a = [{"structures": "ppfla", "views": 8, "ppfla:k": 4}, {"structures": "psppsll", "views": 16}]
        spec = sweep_file(q, a, {"name": "brief", "frames": 3, "warmup": 1, "target": 0, "spp": 16}, "t")
        self.assertEqual(spec["axes"]["structures"], "ppfla")
        self.assertEqual(spec["include"], [a[1]])
        self.assertEqual(spec["settings"]["reference"]["spp"], 16)


class CountsFromOneSource(unittest.TestCase):
    """advise's counts (issue 37): the console's line, summary.md and result.json say the
    numbers counts_of() derives from the stages' costs; the census plans and is no
    measuring stage; "the front: N of M" heads a table of N rows."""

    def stages(self):
        model, costs = Model(noise=0.3), []

        def measure(cands, level, stage):
            costs.append({"stage": stage, "configurations": len(cands), "keys": [c.key for c in cands],
                          "precision": f"level {level}", "wall_s_this_call": 1.0, "wall_s_recorded": 0.5})
            return model(cands, level, stage)

        cands = space()
        costs.append({"stage": "census", "configurations": len(cands), "keys": [c.key for c in cands],
                      "planned_only": True, "precision": "memory plan", "wall_s_this_call": 0.25,
                      "wall_s_recorded": 0.25})
        goal = Goal(budget_ms=40)
        search = Search(cands, goal, 3, measure, lambda e: None)
        outcome = search.run()
        return cands, costs, goal, search, outcome

    def test_counts_and_sentences_agree(self):
        cands, costs, goal, search, outcome = self.stages()
        counts = counts_of(costs, len(cands))
        measuring = [c for c in costs if not c.get("planned_only")]
        self.assertEqual(counts["stages"], len(measuring))
        self.assertEqual(counts["census_stages"], 1)
        self.assertEqual(counts["planned"], len(cands))
        self.assertEqual(counts["measured"], sum(c["configurations"] for c in measuring))
        distinct = {k for c in measuring for k in c["keys"]}
        self.assertEqual(counts["configurations"], len(distinct))
        self.assertLess(counts["configurations"], counts["measured"])  # some measured at two levels
        self.assertEqual(counts["wall_s_recorded"], 0.25 + 0.5 * len(measuring))
        sentence = counts_sentence(counts)
        self.assertIn(f"{len(distinct)} configurations of {len(cands)} measured, {counts['measured']} "
                      f"measurements in {len(measuring)} measuring stages", sentence)
        self.assertTrue(sentence.startswith(f"The census planned {len(cands)} configurations"), sentence)
        import tempfile
        with tempfile.TemporaryDirectory() as out:
            result = {"recommended": outcome.recommended, "answer_lines": ["answer"], "counts": counts}
            folder = write_report(out, result, search, goal, "mse", costs, "title")
            with open(os.path.join(folder, "summary.md"), encoding="utf-8") as f:
                summary = f.read()
        self.assertIn(sentence + ".", summary)
        # "The front: N configurations of the M measured ..." and then N rows
        head = next(line for line in summary.splitlines() if line.startswith("The front: "))
        n_front = int(head.split()[2])
        section = summary.split("## Front found")[1].split("## Pruned")[0]
        rows = [line for line in section.splitlines() if line.startswith("| ") and not line.startswith("| configuration")]
        self.assertEqual(len(rows), n_front, summary)
        # no other count of configurations or stages in the summary than these
        self.assertNotIn("Among the", summary)
        self.assertNotIn("Configurations measured:", summary)


class AgainstAnExhaustiveRun(unittest.TestCase):
    """scripts/advise_vs_exhaustive.py's judgement (issue 34): an exhaustive run of one
    repetition refutes advise's answer only where it measured the answer surely over the
    budget, or something surely within it with less error; an answer whose interval straddles
    the budget there, with less error than the run's best, is a tie across the budget line."""

    @staticmethod
    def row(cid, ms, low, high, mse, noise=1e-6, status="ok"):
        return {"config_id": cid, "status": status, "frame_ms_median": str(ms), "frame_ms_ci_low": str(low),
                "frame_ms_ci_high": str(high), "mse": str(mse), "ref_noise_mse": str(noise),
                "bytes_allocated": "1000", "max_depth_complexity": "4"}

    def setUp(self):
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
        import advise_vs_exhaustive
        self.judge = advise_vs_exhaustive
        rows = [self.row("sure", 6, 5, 7, 0.004),          # surely within 10 ms: the run's best
                self.row("straddles", 9, 7, 12, 0.002),    # less error, not placeable
                self.row("over", 14, 11, 17, 0.001),       # surely over
                self.row("tie", 6.5, 5.5, 7.5, 0.004)]     # the best's error
        self.rows = {r["config_id"]: r for r in rows}
        self.goal = Goal(budget_ms=10)

    def stands(self, rec):
        return self.judge.how_it_stands(self.rows, {"recommended": rec}, self.goal)

    def test_best_error_tie_and_a_tie_across_the_budget_line_stand(self):
        self.assertEqual(self.stands("sure"), "best")
        self.assertEqual(self.stands("tie"), "tied on error")
        self.assertEqual(self.stands("straddles"), "across the budget line")

    def test_surely_over_or_beaten_by_a_surely_within_configuration_is_refuted(self):
        self.assertTrue(self.stands("over").startswith("refuted: surely over"), self.stands("over"))
        self.rows["worse"] = self.row("worse", 8, 7, 9, 0.009)
        self.assertIn("sure is surely within the budgets with less error", self.stands("worse"))
        self.rows["straddles"]["mse"] = "0.005"  # straddling and worse than the best: refuted
        self.assertTrue(self.stands("straddles").startswith("refuted"))
        self.assertTrue(self.judge.how_it_stands(self.rows, {"recommended": None}, self.goal).startswith("refuted"))



class VerifyRepeatedPrecision(unittest.TestCase):
    def test_uncertain_candidates_are_repeated_in_processes_of_their_own(self):
        # Repetitions in one process share its offset and would not narrow the interval
        # (harness/measure/run_to_run_spread.h); the sweep file must ask for processes.
        from ldmadvise.measure import VERIFY_UNCERTAIN
        spec = sweep_file({"scene": "cornell", "pass": "ao", "image_size": "32x32"},
                          [{"structures": "psppsll", "views": 4, "r_ldm": 32}], VERIFY_UNCERTAIN, "t")
        self.assertEqual(spec["settings"]["timing"]["repetitions"], 3)
        self.assertEqual(spec["settings"]["timing"]["isolation"], "process")

    def test_the_search_levels_count_no_work_and_the_verification_does(self):
        from ldmadvise.measure import LEVELS, VERIFY, VERIFY_UNCERTAIN
        question = {"scene": "cornell", "pass": "ao", "image_size": "32x32"}
        one = [{"structures": "psppsll", "views": 4, "r_ldm": 32}]
        for level in LEVELS:
            self.assertIs(sweep_file(question, one, level, "t")["settings"]["work"], False)
        for verify in (VERIFY, VERIFY_UNCERTAIN):
            self.assertNotIn("work", sweep_file(question, one, verify, "t")["settings"])


class VerificationFakes:
    """A search's states and a stage runner that returns given measurements, for the rounds
    after the first verification."""

    class State:
        def __init__(self, m):
            self.measurement, self.history = m, []

    class Runner:
        def __init__(self, truth, recorded_s=0.0, per_measurement_s=None):
            self.truth, self.stages, self.events, self.recorded = truth, [], [], recorded_s
            self.per_measurement_s, self.costs = per_measurement_s, []

        def run_stage(self, keys, precision, stage):
            self.stages.append((stage, list(keys), precision["name"]))
            repetitions = precision.get("repetitions", 1)
            recorded = None if self.per_measurement_s is None else self.per_measurement_s * len(keys) * repetitions
            self.costs.append({"stage": stage, "configurations": len(keys), "repetitions": repetitions,
                               "wall_s_recorded": recorded})
            self.recorded += recorded or 0.0
            return {k: self.truth[k] for k in keys}, stage, {k: {} for k in keys}, stage + "/run"

        def recorded_s(self):
            return self.recorded

        def log(self, event):
            self.events.append(event)

    @staticmethod
    def unlimited():
        """A budget that learnt nothing: every round fits."""
        from ldmadvise.cost import VerificationBudget
        return VerificationBudget(0.25, 60)

    @staticmethod
    def m(time, low, high, error):
        return Measurement(time=time, time_low=low, time_high=high, error=error, error_band=0.0, memory=1)


class VerifyMoreUncertain(VerificationFakes, unittest.TestCase):
    """The rounds after the first verification (ldmbench_advise.verify_more_uncertain)."""

    def run_rounds(self, truth, search_measured, uncertain, verified, budget=None, recorded_s=0.0):
        import ldmbench_advise
        goal = Goal(budget_ms=6.0)
        search = type("S", (), {})()
        search.states = {k: self.State(m) for k, m in search_measured.items()}
        outcome = type("O", (), {"uncertain": uncertain})()
        runner = self.Runner(truth, recorded_s)
        vsource = {k: ("verify", {}, "verify/run") for k in verified}
        ldmbench_advise.verify_more_uncertain(runner, search, goal, outcome, verified, vsource, "verify",
                                              budget or self.unlimited())
        return runner, verified, vsource

    def test_unverified_better_candidates_are_verified_until_none_beats_the_best_within(self):
        # The Cornell box of 2026-12-04: the recommendation (error 0.0098) surely within; the
        # first round's two uncertain candidates (0.0031) still across the line; two at 0.0079
        # unverified, surely within when measured; one more at 0.0031, over when measured.
        rec, a, b, c, d, e = "rec", "n16-a", "n16-b", "n8r64-a", "n8r64-b", "n16-c"
        verified = {rec: self.m(3.2, 2.9, 3.5, 0.0098), a: self.m(5.5, 4.8, 6.3, 0.0031),
                    b: self.m(6.1, 5.6, 6.5, 0.0031)}
        race = {c: self.m(4.6, 3.1, 6.8, 0.0079), d: self.m(5.3, 3.9, 7.3, 0.0079), e: self.m(6.1, 5.2, 7.1, 0.0031)}
        truth = {c: self.m(4.8, 4.2, 5.6, 0.0079), d: self.m(4.2, 3.6, 4.9, 0.0079), e: self.m(6.6, 6.1, 7.2, 0.0031)}
        runner, verified, vsource = self.run_rounds(truth, dict(race), [a, b, c, d, e], verified)
        self.assertEqual(runner.stages, [("verify-uncertain-1", [c, d], "verify-repeated"),
                                         ("verify-uncertain-2", [e], "verify-repeated")])
        self.assertEqual(verified[d].time, 4.2)
        self.assertEqual(vsource[d][0], "verify-uncertain-1")  # the record the answer would report
        self.assertEqual(vsource[d][2], "verify-uncertain-1/run")

    def test_nothing_more_is_verified_when_no_unverified_candidate_beats_the_best_within(self):
        rec, worse = "rec", "worse"
        verified = {rec: self.m(3.2, 2.9, 3.5, 0.003)}
        runner, _, _ = self.run_rounds({}, {worse: self.m(5.9, 5.0, 7.0, 0.009)}, [worse], verified)
        self.assertEqual(runner.stages, [])

    def test_at_most_two_more_rounds(self):
        verified = {"rec": self.m(3.2, 2.9, 3.5, 0.01)}
        names = [f"u{i}" for i in range(8)]
        straddling = {k: self.m(6.0, 5.0, 7.0, 0.001 * (i + 1)) for i, k in enumerate(names)}
        runner, _, _ = self.run_rounds(straddling, dict(straddling), names, verified)
        self.assertEqual([len(keys) for _, keys, _ in runner.stages], [2, 2])

    def test_a_dear_round_leaves_out_the_next_one_the_first_verification_would_have_allowed(self):
        import ldmbench_advise
        from ldmadvise.cost import VerificationBudget
        budget = VerificationBudget(1.0, 60)
        budget.learn({"configurations": 3, "repetitions": 3, "wall_s_recorded": 2.7})  # 18 s estimated
        verified = {"rec": self.m(3.2, 2.9, 3.5, 0.01)}
        names = [f"u{i}" for i in range(4)]
        straddling = {k: self.m(6.0, 5.0, 7.0, 0.001 * (i + 1)) for i, k in enumerate(names)}
        goal = Goal(budget_ms=6.0)
        search = type("S", (), {})()
        search.states = {k: self.State(m) for k, m in straddling.items()}
        outcome = type("O", (), {"uncertain": names})()
        # The first round's six measurements cost 1 s each, not the verification's 0.3 s: after
        # it (10 + 6 = 16 s recorded) the second, predicted at 6 s, would pass the 18 s.
        runner = self.Runner(straddling, recorded_s=10.0, per_measurement_s=1.0)
        ldmbench_advise.verify_more_uncertain(runner, search, goal, outcome, verified,
                                              {"rec": ("verify", {}, "verify/run")}, "verify", budget)
        self.assertEqual([stage for stage, _, _ in runner.stages], ["verify-uncertain-1"])
        self.assertEqual([r["stage"] for r in budget.skipped], ["verify-uncertain-2"])

    def test_a_round_over_the_verification_budget_is_left_out_and_named(self):
        # The Cornell box of 2026-12-05: the first verification recorded 3.0 s for 3
        # candidates x 3 repetitions; 60 configurations make an exhaustive sweep of about 20 s,
        # a quarter of it 5 s; the search and the verification had recorded 9 s.
        from ldmadvise.cost import VerificationBudget
        budget = VerificationBudget(0.25, 60)
        budget.learn({"stage": "verify", "configurations": 3, "repetitions": 3, "wall_s_recorded": 3.0})
        verified = {"rec": self.m(3.2, 2.9, 3.5, 0.01)}
        straddling = {"u1": self.m(6.0, 5.0, 7.0, 0.002), "u2": self.m(6.0, 5.0, 7.0, 0.003)}
        runner, _, _ = self.run_rounds(straddling, dict(straddling), ["u1", "u2"], verified, budget, recorded_s=9.0)
        self.assertEqual(runner.stages, [])
        self.assertEqual([(r["stage"], r["keys"]) for r in budget.skipped], [("verify-uncertain-1", ["u1", "u2"])])
        self.assertEqual(runner.events[0]["event"], "skipped")
        self.assertIn("estimated at 20.0 s", runner.events[0]["why"])
        # The same round within a larger share (a rerun with --cost-share 1) is measured.
        roomy = VerificationBudget(1.0, 60)
        roomy.learn({"stage": "verify", "configurations": 3, "repetitions": 3, "wall_s_recorded": 3.0})
        runner, _, _ = self.run_rounds(straddling, dict(straddling), ["u1", "u2"], verified, roomy, recorded_s=9.0)
        self.assertEqual([stage for stage, _, _ in runner.stages], ["verify-uncertain-1"])
        self.assertEqual(roomy.skipped, [])


class SettleBudgetLine(VerificationFakes, unittest.TestCase):
    """The last round (ldmbench_advise.settle_budget_line): a verified candidate still across
    the budget line, better than the best surely within, measured with twice the repetitions."""

    def settle(self, truth, verified, budget=None, recorded_s=0.0):
        import ldmbench_advise
        goal = Goal(budget_ms=6.5)
        search = type("S", (), {})()
        search.states = {k: self.State(m) for k, m in verified.items()}
        runner = self.Runner(truth, recorded_s)
        vsource = {k: ("verify", {}, "verify/run") for k in verified}
        ldmbench_advise.settle_budget_line(runner, search, goal, verified, vsource, "verify",
                                           budget or self.unlimited())
        return runner, verified, vsource

    def test_the_candidates_across_the_line_are_measured_with_more_repetitions_likely_within_first(self):
        # The Cornell box of 2026-12-05 at 6.5 ms: the answer (0.0098) surely within; PPFLA N 8
        # R_LDM 64 (0.0079) across the line by its upper bound; PSPPSLL N 16 (0.0031) across
        # with its median over the budget, so less likely within; N 32 (0.0013) too, worse
        # still: the first two are settled, likely within first.
        rec, n8, n16, n32 = "rec", "ppfla-n8-r64", "psppsll-n16-r32", "psppsll-n32-r32"
        verified = {rec: self.m(4.13, 3.29, 5.19, 0.0098), n8: self.m(5.23, 4.11, 6.66, 0.0079),
                    n16: self.m(7.21, 6.13, 8.49, 0.0031), n32: self.m(12.0, 9.0, 16.0, 0.0013)}
        truth = {n8: self.m(5.1, 4.6, 5.7, 0.0079), n16: self.m(7.0, 6.6, 7.4, 0.0031)}
        runner, verified, vsource = self.settle(truth, verified)
        # Likely within first, then the least over the budget (not the least error: N 32 is
        # twice over it).
        self.assertEqual(runner.stages, [("verify-settle", [n8, n16], "verify-settle")])
        self.assertEqual(verified[n8].time_high, 5.7)
        self.assertEqual(vsource[n8], ("verify-settle", {n8: {}, n16: {}}, "verify-settle/run"))

    def test_nothing_is_settled_when_no_candidate_across_the_line_beats_the_best_within(self):
        rec, tied, worse = "rec", "tied", "worse"
        verified = {rec: self.m(4.1, 3.3, 5.2, 0.0079), tied: self.m(5.2, 4.1, 6.7, 0.0079),
                    worse: self.m(6.0, 5.0, 7.0, 0.0098)}
        runner, _, _ = self.settle({}, verified)
        self.assertEqual(runner.stages, [])

    def test_the_settle_round_is_left_out_when_it_would_pass_the_verification_budget(self):
        from ldmadvise.cost import VerificationBudget
        rec, n8 = "rec", "ppfla-n8-r64"
        verified = {rec: self.m(4.13, 3.29, 5.19, 0.0098), n8: self.m(5.23, 4.11, 6.66, 0.0079)}
        budget = VerificationBudget(0.25, 60)
        budget.learn({"stage": "verify", "configurations": 2, "repetitions": 3, "wall_s_recorded": 1.2})
        # 60 x 0.2 s = 12 s, a quarter 3 s: one candidate's six repetitions (1.2 s) fit after
        # 1.5 s, not after 2 s.
        runner, _, _ = self.settle({n8: self.m(5.1, 4.6, 5.7, 0.0079)}, dict(verified), budget, recorded_s=1.5)
        self.assertEqual([stage for stage, _, _ in runner.stages], ["verify-settle"])
        runner, _, _ = self.settle({n8: self.m(5.1, 4.6, 5.7, 0.0079)}, dict(verified), budget, recorded_s=2.0)
        self.assertEqual(runner.stages, [])
        self.assertEqual([r["stage"] for r in budget.skipped], ["verify-settle"])

    def test_without_a_candidate_surely_within_those_across_the_line_are_settled_best_first(self):
        a, b = "a", "b"
        verified = {a: self.m(6.0, 5.0, 7.0, 0.004), b: self.m(6.2, 5.1, 7.4, 0.002)}
        runner, _, _ = self.settle({a: self.m(6.0, 5.0, 7.0, 0.004), b: self.m(6.1, 5.8, 6.4, 0.002)}, verified)
        self.assertEqual(runner.stages, [("verify-settle", [b, a], "verify-settle")])  # best first


class VerificationBudgetTest(unittest.TestCase):
    """ldmadvise/cost.py: the estimate of an exhaustive sweep and what fits in a share of it."""

    def test_the_estimate_is_the_verifications_time_per_measurement_times_the_space(self):
        from ldmadvise.cost import VerificationBudget
        b = VerificationBudget(0.25, 60)
        self.assertIsNone(b.exhaustive_s())
        self.assertIsNone(b.refusal(1e9, ["a"], 6))  # nothing learnt: every round fits
        b.learn({"configurations": 4, "repetitions": 3, "wall_s_recorded": 6.0})
        self.assertAlmostEqual(b.exhaustive_s(), 30.0)
        self.assertIsNone(b.refusal(6.0, ["a"], 3))          # 6 + 1.5 <= 7.5
        self.assertIsNotNone(b.refusal(6.1, ["a"], 3))       # 7.6 > 7.5
        self.assertIsNotNone(b.refusal(0.0, ["a", "b"], 24))  # a round alone past the share
        summary = b.summary(6.0)
        self.assertEqual((summary["exhaustive_estimate_s"], summary["per_measurement_s"]), (30.0, 0.5))

    def test_a_round_dearer_than_the_first_verification_raises_the_next_rounds_prediction(self):
        from ldmadvise.cost import VerificationBudget
        b = VerificationBudget(1.0, 60)
        b.learn({"configurations": 3, "repetitions": 3, "wall_s_recorded": 2.7})   # 0.3 s each: 18 s
        self.assertIsNone(b.refusal(12.0, ["a", "b"], 6))                           # 12 + 3.6 <= 18
        b.observe({"configurations": 2, "repetitions": 3, "wall_s_recorded": 3.6})  # 0.6 s each
        self.assertIsNotNone(b.refusal(12.0, ["a", "b"], 6))                        # 12 + 7.2 > 18
        self.assertAlmostEqual(b.exhaustive_s(), 18.0)  # the estimate stays the first verification's
        b.observe({"configurations": 2, "repetitions": 3, "wall_s_recorded": 0.6})  # a cheap one: the dearest stands
        self.assertIsNotNone(b.refusal(12.0, ["a", "b"], 6))

    def test_a_verification_without_recorded_times_teaches_nothing(self):
        from ldmadvise.cost import VerificationBudget
        b = VerificationBudget(0.25, 60)
        b.learn({"configurations": 2, "wall_s_recorded": None})
        self.assertIsNone(b.exhaustive_s())

    def test_the_share_is_checked_with_the_options_name(self):
        import subprocess
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "advise",
                              "ldmbench_advise.py")
        for bad in ("0", "-1", "nan"):
            r = subprocess.run([sys.executable, script, "--ldmbench", "x", "--axes", "x", "--scene", "cornell",
                                "--out", "/nonexistent/x", "--budget-ms", "5", "--cost-share", bad],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 2, bad)
            self.assertIn("--cost-share", r.stderr)


class FreezeCalibration(unittest.TestCase):
    """ldmbench_advise.freeze_calibration: one spread handed to every stage."""

    def fake_ldmbench(self, current):
        """A stand-in for ldmbench that answers `calibrate --show --json` (current or stale until
        a `calibrate` ran) and logs its calls."""
        import tempfile
        folder = tempfile.mkdtemp(prefix="ldm-fake-calibrate-")
        path = os.path.join(folder, "ldmbench")
        with open(path, "w") as f:
            f.write(f"""#!/bin/sh
echo "$@" >> {folder}/calls
if [ "$2" = "--show" ]; then
  if [ -f {folder}/probed ] || [ {int(current)} = 1 ]; then
    echo '{{"file": "{folder}/spread.json", "cached": true, "spread": 0.2, "current": true, "stale": ""}}'
  else
    echo '{{"file": "{folder}/spread.json", "cached": true, "spread": 0.3, "current": false, "stale": "older than a day"}}'
  fi
else
  touch {folder}/probed
fi
""")
        os.chmod(path, 0o755)
        return path, folder

    def freeze(self, ldmbench, launcher="local", env=None):
        import ldmbench_advise
        events, saved = [], os.environ.pop("LDM_CALIBRATION", None)
        try:
            if env is not None:
                os.environ["LDM_CALIBRATION"] = env
            ldmbench_advise.freeze_calibration(ldmbench, launcher, events.append)
            return events, os.environ.get("LDM_CALIBRATION")
        finally:
            os.environ.pop("LDM_CALIBRATION", None)
            if saved is not None:
                os.environ["LDM_CALIBRATION"] = saved

    def calls(self, folder):
        with open(os.path.join(folder, "calls")) as f:
            return [line.split() for line in f]

    def test_a_current_entry_is_handed_to_the_stages_without_probing(self):
        ldmbench, folder = self.fake_ldmbench(current=True)
        events, handed = self.freeze(ldmbench)
        self.assertEqual(handed, os.path.join(folder, "spread.json"))
        self.assertEqual(self.calls(folder), [["calibrate", "--show", "--json"]])
        self.assertIsNone(events[0]["probed_because"])

    def test_a_stale_entry_is_probed_once_first(self):
        ldmbench, folder = self.fake_ldmbench(current=False)
        events, handed = self.freeze(ldmbench)
        self.assertEqual(handed, os.path.join(folder, "spread.json"))
        self.assertEqual([c[:2] for c in self.calls(folder)],
                         [["calibrate", "--show"], ["calibrate"], ["calibrate", "--show"]])
        self.assertEqual(events[0]["probed_because"], "older than a day")
        self.assertEqual(events[0]["spread"], 0.2)

    def test_a_users_choice_and_slurm_stages_are_left_alone(self):
        ldmbench, folder = self.fake_ldmbench(current=True)
        self.assertEqual(self.freeze(ldmbench, env="skip"), ([], "skip"))
        self.assertEqual(self.freeze(ldmbench, launcher="slurm"), ([], None))
        self.assertFalse(os.path.exists(os.path.join(folder, "calls")))


if __name__ == "__main__":
    unittest.main(verbosity=1)
