"""What advise may spend on verification after its first round (docs/guide/advise.md, "Cost").

advise is worth running only while it costs less than measuring the whole space. The first
verification is part of the answer and always runs. The rounds after it, the repeated
verification of uncertain candidates and the settling of the budget line
(ldmbench_advise.verify_more_uncertain, settle_budget_line), measure each candidate in 3 or
6 processes: on the Cornell box (2026-12-05, 07:50) they were 9.6 of advise's 19 s against an
exhaustive sweep of 33 s. They are not always needed (that morning the first verification's
answer alone would have stood against both exhaustive runs in all six questions) and not
always spare (at 11:26, without them, both runs refuted the answer). So a further round runs
only while advise's recorded time, the round's predicted time added, stays within a share of
what one exhaustive sweep of the space would record. The rounds it leaves out are named in
the answer with their candidates, never dropped silently.

Times are the records' own (`wall_seconds`, StageRunner.recorded_s): a resumed advise, whose
stages are read back instead of measured, decides as the first call did.
"""

# The share of an exhaustive sweep advise may spend before a further round (--cost-share).
# By default the rounds stop only where advise would cost what measuring the whole space
# costs: an answer an exhaustive run refutes is worse than a slower one. On the Cornell box
# (2026-12-05, 11:26) a quarter left out the round that would have verified the exhaustive
# runs' best, and both runs refuted the answer; a user who wants the cheaper answer, with
# the unsettled candidates named, asks for it (0.25).
DEFAULT_SHARE = 1.0


class VerificationBudget:
    """An exhaustive sweep measures every configuration of the space once at the
    verification's precision. Its cost is estimated from the first verification's records:
    their recorded seconds per configuration and repetition, times the space's
    configurations. The verified candidates are those within the budgets, cheaper than most
    of the space, so the estimate tends to be low (0.26-1.3 of the exhaustive records' own
    time on 2026-12-05's six questions): a round is left out sooner, never later."""

    def __init__(self, share, configurations):
        self.share, self.configurations = share, configurations
        self.per_measurement_s = None  # the first verification's recorded seconds per configuration and repetition
        self.per_round_measurement_s = None  # the dearest a round has cost so far, the same way
        self.skipped = []              # the rounds left out: stage, keys, why

    @staticmethod
    def _per_measurement(cost):
        measurements = cost["configurations"] * cost.get("repetitions", 1)
        recorded = cost.get("wall_s_recorded")
        return recorded / measurements if recorded and measurements else None

    def learn(self, cost):
        """Reads the first verification's cost (an entry of StageRunner.costs)."""
        self.per_measurement_s = self._per_measurement(cost)

    def observe(self, cost):
        """Reads a round's cost: the next round is predicted at the dearest rate seen. The
        rounds' candidates straddle the budget and their repetitions can run to the time cap:
        on the Cornell box (2026-12-05, 12:00) a settle round predicted at 3.1 s from the first
        verification took 7.8 s, after a round of 2.6 s for 2 candidates x 3 repetitions."""
        rate = self._per_measurement(cost)
        if rate is not None:
            self.per_round_measurement_s = max(rate, self.per_round_measurement_s or 0.0)

    def exhaustive_s(self):
        return None if self.per_measurement_s is None else self.per_measurement_s * self.configurations

    def refusal(self, spent_s, keys, repetitions):
        """None when a round measuring `keys` with `repetitions` each fits; else why not. With
        nothing learnt (no recorded times) every round fits, as before this budget existed."""
        exhaustive = self.exhaustive_s()
        if exhaustive is None:
            return None
        rate = max(self.per_measurement_s, self.per_round_measurement_s or 0.0)
        predicted = rate * len(keys) * repetitions
        if spent_s + predicted <= self.share * exhaustive:
            return None
        return (f"it would bring advise's recorded time to {spent_s + predicted:.1f} s ({spent_s:.1f} s so far), "
                f"over {self.share:g} of an exhaustive sweep's, estimated at {exhaustive:.1f} s "
                f"({self.configurations} configurations at {self.per_measurement_s:.2f} s, the first "
                f"verification's time per configuration and repetition; the round predicted at "
                f"{rate:.2f} s per configuration and repetition)")

    def skip(self, stage, keys, why):
        self.skipped.append({"stage": stage, "keys": list(keys), "why": why})

    def summary(self, spent_s):
        exhaustive = self.exhaustive_s()
        return {"share": self.share, "exhaustive_estimate_s": None if exhaustive is None else round(exhaustive, 2),
                "per_measurement_s": None if self.per_measurement_s is None else round(self.per_measurement_s, 3),
                "recorded_s": round(spent_s, 2), "skipped": self.skipped}
