"""The search of `ldmbench advise`: which configurations to measure, how precisely, and
which to drop, given only a `measure(candidates, level)` callback. No I/O here, so the
unit tests (tests/advise/test_search.py) drive it with synthetic cost and error models.

Why this shape (docs/guide/advise.md, "Strategy"). The space is mostly discrete: a handful
of structures, each with a few discrete parameters (k, load factor), crossed with a short
ladder of N and R_LDM. Continuous optimisers (scipy.optimize, Gaussian-process Bayesian
optimisation) need a smooth objective over a continuous domain and spend their first
evaluations learning a surrogate; here one evaluation (a configuration measured) costs as
much as a surrogate would save, and the objective is a step function of categorical
inputs. What the space does have is order: on one structure's lattice of (N, R_LDM), frame
time and memory do not fall and AO error does not rise as N and R_LDM grow. So:

  1. explore (brief precision): per structure lattice, measure the middle undecided point;
     a point surely over a budget removes every larger point of its lattice, a point surely
     within the budgets removes every smaller one (dominated: no less error). Before it, the
     census (`ldmbench sweep --memory-plan`: the fragments counted, each structure's storage
     planned, nothing built or timed) removes every configuration whose exact allocation is
     over the memory budget, and fixed arrays too short for that geometry (lossy). Repeat until every point is measured or removed: about
     log2 of the lattice's size per structure instead of all of it.
  2. race (successive halving): the survivors are measured again at rising precision (more
     frames, a reference with more samples, so smaller tie bands); at each level a
     candidate beaten beyond the bands by one that surely meets the budgets is dropped, and
     at most the better half (never a candidate tied with the best) goes on.
  3. stop when one candidate is left, or all left are tied with the best and surely within
     the budgets, or the last level is reached; recommend the best (its ties beside it).
  4. verify: the recommendation and its ties measured at a normal run's precision.

Time is judged by its interval (the record's 95 % interval of the median), error by its
band (the reference's own noise), memory exactly: the tie rules of the report
(scripts/report/ldmreport/ties.py).
"""
import math
import os
import sys
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional

# The tie rules are the report's own (installed beside this folder, as in the sources).
_REPORT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "report"))
if _REPORT not in sys.path:
    sys.path.insert(0, _REPORT)
from ldmreport import ties  # noqa: E402

YES, NO, MAYBE = "yes", "no", "maybe"


@dataclass(frozen=True)
class Candidate:
    key: str                 # the configuration id
    group: str               # the lattice it lies on: everything but N and R_LDM
    views: int
    r_ldm: int
    k: Optional[int] = None  # a fixed array's entries per pixel (lossy when the census is deeper)

    def covers(self, other):
        """self >= other in both N and R_LDM (the lattice's order)."""
        return self.views >= other.views and self.r_ldm >= other.r_ldm


@dataclass
class Measurement:
    time: float              # frame time median, ms
    time_low: float          # its 95 % interval
    time_high: float
    error: float             # lower is better (MSE, or 1 - MSSIM)
    error_band: float        # the reference's own noise on that error
    memory: int              # bytes allocated, exact
    status: str = "ok"       # ok, lossy, invalid, failed
    detail: str = ""
    max_depth: Optional[int] = None  # the census's deepest LDM pixel at this geometry
    level: int = 0


@dataclass
class Goal:
    budget_ms: Optional[float] = None
    budget_bytes: Optional[int] = None
    max_error: Optional[float] = None  # given: the fastest within it; else the least error

    @property
    def minimize(self):
        return "time" if self.max_error is not None else "error"

    def time_verdict(self, m):
        if self.budget_ms is None or m.time_high <= self.budget_ms:
            return YES
        return NO if m.time_low > self.budget_ms else MAYBE

    def error_verdict(self, m):
        if self.max_error is None or m.error + m.error_band <= self.max_error:
            return YES
        return NO if m.error - m.error_band > self.max_error else MAYBE

    def memory_fits(self, m):
        return self.budget_bytes is None or m.memory <= self.budget_bytes

    def likely_within(self, m):
        """The medians within every budget (the interval may still straddle one)."""
        return (self.memory_fits(m) and (self.budget_ms is None or m.time <= self.budget_ms) and
                (self.max_error is None or m.error <= self.max_error))

    def overshoot(self, m):
        """How far the medians lie over the budgets, as the largest ratio of a median to its
        budget (memory in bytes, time, error); 1 or less: within every budget."""
        ratios = [1.0]
        if self.budget_bytes:
            ratios.append(m.memory / self.budget_bytes)
        if self.budget_ms:
            ratios.append(m.time / self.budget_ms)
        if self.max_error:
            ratios.append(m.error / self.max_error)
        return max(ratios)

    def verdict(self, m):
        """yes: surely within every budget; no: surely outside one; maybe otherwise."""
        if not self.memory_fits(m):
            return NO
        v = (self.time_verdict(m), self.error_verdict(m))
        return NO if NO in v else (YES if v == (YES, YES) else MAYBE)


# Tie bands: scripts/report/ldmreport/ties.py on this module's values (time: the intervals
# overlap; error: within the larger reference noise or float summation order).
def time_measure(m):
    return ties.Measure(m.time, m.time_low, m.time_high)


def error_measure(m):
    return ties.Measure(m.error, band=m.error_band)


def time_tied(a, b):
    return ties.tied(time_measure(a), time_measure(b))


def error_tied(a, b):
    return ties.tied(error_measure(a), error_measure(b))


def primary_tied(goal, a, b):
    return time_tied(a, b) if goal.minimize == "time" else error_tied(a, b)


def primary_value(goal, m):
    return m.time if goal.minimize == "time" else m.error


def beats(goal, a, b):
    """a is better than b on the goal's criterion beyond the tie band."""
    return not primary_tied(goal, a, b) and primary_value(goal, a) < primary_value(goal, b)


def rank_key(goal, m):
    """Best first: the criterion, then the other one, then memory."""
    other = m.error if goal.minimize == "time" else m.time
    return (primary_value(goal, m), other, m.memory)


def choose_best(goal, items, measurement_of=lambda x: x):
    """The best of `items` on the goal's criterion where it tells them apart, and among those
    tied with the leader on it, the best on the other criterion (then memory): a difference
    inside the bands never decides."""
    if not items:
        return None
    lead = min(items, key=lambda x: rank_key(goal, measurement_of(x)))
    tied = [x for x in items if primary_tied(goal, measurement_of(x), measurement_of(lead))]
    other = (lambda m: m.error) if goal.minimize == "time" else (lambda m: m.time)
    return min(tied, key=lambda x: (other(measurement_of(x)), measurement_of(x).memory))


@dataclass
class CensusPlan:
    """What the census says before anything is built or measured: the deepest LDM pixel per
    geometry (N, R_LDM), and per configuration the exact bytes its structure allocates for
    this scene (`ldmbench sweep --memory-plan`), or why it cannot run at all."""
    depths: Dict[tuple, int] = field(default_factory=dict)
    memory: Dict[str, int] = field(default_factory=dict)
    refused: Dict[str, str] = field(default_factory=dict)


@dataclass
class State:
    candidate: Candidate
    measurement: Optional[Measurement] = None
    pruned: Optional[str] = None   # why, when dropped
    pruned_by: Optional[str] = None  # the candidate that beat or dominated it (revived if that one fails)
    stage: str = ""                # where it was dropped or last measured
    history: List[Measurement] = field(default_factory=list)


@dataclass
class Outcome:
    recommended: Optional[str]
    ties: List[str]
    survivors: List[str]
    why: str                       # how the search stopped
    # Across the budget line: candidates whose interval straddles a budget (neither surely
    # within nor surely over) that are better than the recommendation, or tied with it, on
    # the goal's criterion. Measured again with repetitions before they are dropped.
    uncertain: List[str] = field(default_factory=list)


class Search:
    """`measure(candidates, level, stage)` returns {key: Measurement}; level 0 is the brief
    precision, `levels - 1` the most precise race level. `log(event_dict)` journals."""

    def __init__(self, candidates: List[Candidate], goal: Goal, levels: int,
                 measure: Callable, log: Callable = lambda event: None, census: Callable = None):
        if not candidates:
            raise ValueError("empty space")
        self.goal, self.levels, self.measure, self.log = goal, levels, measure, log
        self.census = census  # census([Candidate]) -> CensusPlan
        self.states: Dict[str, State] = {c.key: State(c) for c in candidates}
        self.planned_memory: Dict[str, int] = {}  # the census's exact bytes per configuration
        self.plan_differences: Dict[str, list] = {}  # key -> [planned, measured] where they differ
        self.stage_count = 0

    # ---- bookkeeping
    def prune(self, key, why, stage, by=None):
        s = self.states[key]
        if s.pruned is None:
            s.pruned, s.stage, s.pruned_by = why, stage, by
            self.log({"event": "pruned", "config_id": key, "why": why, "stage": stage})

    def _revive_dependents(self, key, stage):
        """`key` turned out outside a budget: what was dropped only because it beat or
        dominated them comes back (measured again at the race's current level)."""
        for s in self.states.values():
            if s.pruned_by == key:
                s.pruned, s.pruned_by, s.stage = None, None, stage
                self.log({"event": "revived", "config_id": s.candidate.key, "stage": stage,
                          "why": f"{key}, which had beaten or dominated it, is outside the budgets"})

    def alive(self):
        return [s for s in self.states.values() if s.pruned is None]

    def _measure(self, keys, level, stage):
        self.stage_count += 1
        results = self.measure([self.states[k].candidate for k in keys], level, stage)
        for k in keys:
            if k not in results:
                raise RuntimeError(f"{stage}: no measurement of {k}")
            m = results[k]
            m.level = level
            self.states[k].measurement = m
            self.states[k].history.append(m)
            self.states[k].stage = stage
            planned = self.planned_memory.get(k)
            if planned is not None and m.status == "ok" and m.memory != planned:
                # The plan pruned on these bytes: a difference is journaled, never hidden.
                self.plan_differences[k] = [planned, m.memory]
                self.log({"event": "plan_differs", "config_id": k, "stage": stage,
                          "planned_bytes": planned, "measured_bytes": m.memory})
        return results

    # ---- rules
    def _apply_census(self, m, at, stage):
        """Fixed arrays shorter than the census's deepest pixel at this geometry are lossy."""
        if m.max_depth is None:
            return
        for s in self.alive():
            c = s.candidate
            if c.k is not None and (c.views, c.r_ldm) == (at.views, at.r_ldm) and c.k < m.max_depth \
                    and s.measurement is None:
                self.prune(c.key, f"lossy (census): the deepest LDM pixel holds {m.max_depth} "
                                  f"fragments, more than k = {c.k}", stage)

    def _apply_lattice(self, c, m, stage):
        """Monotone rules on c's own lattice after a brief measurement of c."""
        goal = self.goal
        same = [s for s in self.alive() if s.candidate.group == c.group and s.candidate.key != c.key]
        if not goal.memory_fits(m):
            for s in same:
                if s.candidate.covers(c):
                    self.prune(s.candidate.key, f"memory (lattice): {c.key} already needs "
                                                f"{m.memory} bytes", stage)
        if goal.time_verdict(m) == NO:
            for s in same:
                if s.candidate.covers(c):
                    self.prune(s.candidate.key, f"time (lattice): {c.key} is already slower "
                                                f"than {goal.budget_ms} ms", stage)
        if goal.error_verdict(m) == NO:
            for s in same:
                if c.covers(s.candidate):
                    self.prune(s.candidate.key, f"error (lattice): {c.key} already errs more "
                                                f"than {goal.max_error}", stage)
        if goal.verdict(m) == YES:
            for s in same:
                if goal.minimize == "error" and c.covers(s.candidate):
                    self.prune(s.candidate.key, f"dominated (lattice): {c.key} meets the "
                                                "budgets with no more error", stage, by=c.key)
                if goal.minimize == "time" and s.candidate.covers(c):
                    self.prune(s.candidate.key, f"dominated (lattice): {c.key} meets the "
                                                "error bound and is no slower", stage, by=c.key)

    def _apply_own(self, key, m, stage):
        """What one measurement says of its own candidate; True when it stays."""
        if m.status != "ok":
            self.prune(key, f"{m.status}: {m.detail}" if m.detail else m.status, stage)
        elif not self.goal.memory_fits(m):
            self.prune(key, f"memory: {m.memory} bytes > budget {self.goal.budget_bytes}", stage)
        elif self.goal.time_verdict(m) == NO:
            self.prune(key, f"time: {m.time:.4g} ms [{m.time_low:.4g}, {m.time_high:.4g}] "
                            f"> budget {self.goal.budget_ms} ms", stage)
        elif self.goal.error_verdict(m) == NO:
            self.prune(key, f"error: {m.error:.4g} (band {m.error_band:.2g}) > bound "
                            f"{self.goal.max_error}", stage)
        if self.states[key].pruned is not None:
            self._revive_dependents(key, stage)
        return self.states[key].pruned is None

    def recheck(self, key, stage):
        """A measurement taken outside the search (verification) judged like the race's; True
        when the candidate stays."""
        return self.states[key].pruned is None and self._apply_own(key, self.states[key].measurement, stage)

    @staticmethod
    def _middle(states):
        order = sorted(states, key=lambda s: (s.candidate.views * s.candidate.r_ldm ** 2,
                                              s.candidate.views, s.candidate.r_ldm))
        return order[(len(order) - 1) // 2]

    # ---- stages
    def census_stage(self):
        """The census of every candidate, before anything is built or measured: a
        configuration that cannot run (refused), that allocates more than the memory budget,
        or a fixed array shorter than the deepest pixel (lossy) is dropped here."""
        if self.census is None:
            return
        cands = [s.candidate for s in self.alive()]
        self.log({"event": "stage", "stage": "census", "configurations": len(cands)})
        plan = self.census(cands)
        self.planned_memory = dict(plan.memory)
        for c in cands:
            depth = plan.depths.get((c.views, c.r_ldm))
            planned = plan.memory.get(c.key)
            if c.key in plan.refused:
                self.prune(c.key, f"refused (census): {plan.refused[c.key]}", "census")
            elif planned is not None and self.goal.budget_bytes is not None and planned > self.goal.budget_bytes:
                self.prune(c.key, f"memory (census): allocates {planned} bytes > budget "
                                  f"{self.goal.budget_bytes}", "census")
            elif c.k is not None and depth is not None and c.k < depth:
                self.prune(c.key, f"lossy (census): the deepest LDM pixel holds {depth} fragments, "
                                  f"more than k = {c.k}", "census")

    def explore(self):
        wave = 0
        while True:
            open_states = [s for s in self.alive() if s.measurement is None]
            if not open_states:
                return
            groups = {}
            for s in open_states:
                groups.setdefault(s.candidate.group, []).append(s)
            picks = [self._middle(g).candidate.key for _, g in sorted(groups.items())]
            stage = f"explore-{wave}"
            self.log({"event": "stage", "stage": stage, "level": 0, "measured": picks})
            results = self._measure(picks, 0, stage)
            for key in picks:
                m, c = results[key], self.states[key].candidate
                self._apply_census(m, c, stage)
                self._apply_own(key, m, stage)
                if m.status == "ok":
                    self._apply_lattice(c, m, stage)
            wave += 1

    def race_round(self, stage, level=0):
        """Drops what the current measurements at `level` settle; returns how the race stands."""
        goal = self.goal
        for s in self.alive():
            self._apply_own(s.candidate.key, s.measurement, stage)
        alive = self.alive()
        # A candidate no longer surely within the budgets at this precision beat or dominated
        # others on a premise that no longer holds: they come back.
        for s in alive:
            if s.measurement is not None and goal.verdict(s.measurement) != YES:
                self._revive_dependents(s.candidate.key, stage)
        alive = self.alive()
        # Revived, unmeasured or measured at a lower level: measured at this level first. Errors
        # against references of different precision are not comparable (a noisier reference
        # adds its own variance to the MSE, more than its band), nor are intervals of
        # different frame counts.
        if any(s.measurement is None or s.measurement.level < level for s in alive):
            return alive, None, False
        sure = [s for s in alive if goal.verdict(s.measurement) == YES]
        if not sure:
            return alive, None, False
        best = choose_best(goal, sure, lambda s: s.measurement)
        for s in alive:
            if s is not best and beats(goal, best.measurement, s.measurement):
                self.prune(s.candidate.key, f"beaten: {best.candidate.key} meets the budgets with "
                                            f"{'less time' if goal.minimize == 'time' else 'less error'}"
                                            " beyond the bands", stage, by=best.candidate.key)
        alive = self.alive()
        settled = all(goal.verdict(s.measurement) == YES and
                      primary_tied(goal, s.measurement, best.measurement) for s in alive)
        return alive, best, settled

    def halve(self, alive, best, stage):
        """Successive halving: the better half (at least 2) goes on, with every candidate tied
        with the best."""
        goal = self.goal
        keep = max(2, math.ceil(len(alive) / 2))
        order = sorted(alive, key=lambda s: rank_key(goal, s.measurement))
        for i, s in enumerate(order):
            tied_best = best is not None and primary_tied(goal, s.measurement, best.measurement)
            if i >= keep and not tied_best:
                self.prune(s.candidate.key, f"halved: ranked {i + 1} of {len(order)} by "
                                            f"{goal.minimize} at this precision", stage)

    def _stale(self, level):
        return [s.candidate.key for s in self.alive() if s.measurement is None or s.measurement.level < level]

    def race(self, level=0):
        while True:
            stage = f"race-{level}"
            stale = self._stale(level)
            if stale:  # revived, or never measured: measured at this level first
                self.log({"event": "stage", "stage": stage, "level": level, "measured": stale})
                self._measure(stale, level, stage)
            alive, best, settled = self.race_round(stage, level)
            if self._stale(level):
                continue
            if not alive:
                return Outcome(None, [], [], "every candidate was pruned")
            if len(alive) == 1 and best is not None:
                return self._outcome(best, "one candidate left")
            if settled:
                return self._outcome(best, "the candidates left are tied and within the budgets")
            if level + 1 >= self.levels:
                why = "the most precise level was reached"
                if best:
                    return self._outcome(best, why)
                # None surely within at the race's precision: the best of those that may be is
                # verified (verification at normal precision decides).
                maybe = choose_best(self.goal, alive, lambda s: s.measurement)
                return self._outcome(maybe, why + "; none surely within the budgets, the best that may be "
                                                  "goes to verification")
            self.halve(alive, best, stage)
            level += 1
            keys = [s.candidate.key for s in self.alive()]
            self.log({"event": "stage", "stage": f"race-{level}", "level": level, "measured": keys})
            self._measure(keys, level, f"race-{level}")

    def _outcome(self, best, why):
        goal = self.goal
        ties = [s.candidate.key for s in self.alive() if s is not best and
                goal.verdict(s.measurement) == YES and primary_tied(goal, s.measurement, best.measurement)]
        uncertain = [s.candidate.key for s in self.alive() if s is not best and
                     goal.verdict(s.measurement) == MAYBE and
                     (primary_tied(goal, s.measurement, best.measurement) or
                      primary_value(goal, s.measurement) < primary_value(goal, best.measurement))]
        # Verified first (ldmbench_advise.py verifies the first few): those whose medians are
        # within the budgets, best first; they are the ones a verification is likely to find
        # surely within. Those whose median is over a budget come after.
        uncertain.sort(key=lambda k: (not goal.likely_within(self.states[k].measurement),
                                      rank_key(goal, self.states[k].measurement)))
        return Outcome(best.candidate.key, ties, [s.candidate.key for s in self.alive()], why, uncertain)

    def run(self, level=None):
        """The search; with `level`, the race resumed at that level (after a verification
        found the recommendation outside the budgets)."""
        if level is None:
            self.census_stage()
            self.explore()
            level = 0
        outcome = self.race(level)
        self.log({"event": "outcome", "recommended": outcome.recommended, "ties": outcome.ties,
                  "uncertain": outcome.uncertain, "why": outcome.why})
        return outcome


def pareto_front(goal, measurements):
    """Keys on the time/error front (the report's: no other is better beyond the bands in
    one and no worse in the other), by time."""
    keys = list(measurements)
    front = ties.pareto_front([time_measure(measurements[k]) for k in keys],
                              [error_measure(measurements[k]) for k in keys], False)
    return [keys[i] for i in front]
