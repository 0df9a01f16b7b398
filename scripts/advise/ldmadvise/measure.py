"""Measuring candidates: each stage is an ordinary sweep file run by `ldmbench sweep` into
its own folder under OUT/stages/ (resumable like any sweep: a rerun of advise regenerates
the same file and the sweep skips what it recorded), read back from its records.csv."""
import json
import math
import os
import sys
import time

from .launch import LaunchError
from .search import Measurement
from .space import sweep_file

# Precision of the levels: brief first, a normal run's last (docs/guide/advise.md).
# The search's levels count no work: no decision reads a counter, and the counting replay
# was a third of a brief measurement's wall time on the Cornell box (31 of 90 ms,
# 2026-12-04). The verification, whose record the answer reports, counts.
LEVELS = [
    {"name": "brief", "frames": 3, "warmup": 1, "target": 0, "spp": 16, "work": False},
    {"name": "closer", "frames": 8, "warmup": 1, "target": 0, "spp": 64, "work": False},
]
# A third level at a normal run's precision would cost what verification costs; the
# verification is that level (a failed one resumes the race at the top level above).
# The census stage's sweep file, run as `ldmbench sweep --memory-plan` (nothing built). Its
# builds per run are the brief level's: the plan is the storage a run of more than one build
# records, as every level and the verification are (a run of one build can differ by a
# guess's counter word: docs/guide/sweeps.md#memory-plan).
CENSUS = {"name": "census", "frames": LEVELS[0]["frames"], "warmup": LEVELS[0]["warmup"], "target": 0,
          "reference": False}
# A normal `ldmbench run`: its frames, warm-up, time target and automatic reference.
VERIFY = {"name": "verify", "frames": 5, "warmup": 2, "target": 0.03, "cap_s": 2, "spp": 0, "images": True}
# The verification when a candidate's time interval straddles the budget ("uncertain"): the
# same, with repetitions, whose interval holds the other runs' share of the run-to-run spread
# divided by sqrt(2K) (harness/measure/run_to_run_spread.h) instead of all of it. Each
# repetition in a process of its own: repetitions in one process share its offset from other
# runs, and their interval keeps the whole spread (docs/timing.md, "Widening").
VERIFY_UNCERTAIN = dict(VERIFY, name="verify-repeated", repetitions=3, isolation="process")
# A verified candidate still across the budget line, better than the answer: twice the
# repetitions (ldmbench_advise.settle_budget_line says why).
VERIFY_SETTLE = dict(VERIFY_UNCERTAIN, name="verify-settle", repetitions=6)


class MeasureError(Exception):
    pass


# The one records reader (scripts/ldmrecords, installed beside the advise folder).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
import ldmrecords  # noqa: E402

# A column's value as a float, NaN where absent or not a number.
number = ldmrecords.value


def measurement_of(row, metric):
    """One record as the search sees it (metric: mse, or mssim as 1 - MSSIM)."""
    t = number(row, "frame_ms_median")
    low, high = number(row, "frame_ms_ci_low"), number(row, "frame_ms_ci_high")
    if not (math.isfinite(low) and math.isfinite(high)):  # too few frames for an interval
        low, high = number(row, "frame_ms_min"), number(row, "frame_ms_max")
    if metric == "mssim":
        error = 1 - number(row, "mssim")
        band = (1 - number(row, "ref_noise_mssim")) / 4
    else:
        error, band = number(row, "mse"), number(row, "ref_noise_mse")
    status = row.get("status", "failed")
    detail = row.get("status_detail", "")
    if status == "ok" and row.get("degenerate"):
        status, detail = "degenerate", row["degenerate"]
    if status == "ok" and not all(math.isfinite(v) for v in (t, low, high, error)):
        status, detail = "failed", "no frame time or error in the record"
    depth = number(row, "max_depth_complexity")
    memory = number(row, "bytes_allocated")
    return Measurement(time=t, time_low=low, time_high=high, error=error,
                       error_band=band if math.isfinite(band) and band >= 0 else 0.0,
                       memory=int(memory) if math.isfinite(memory) else 0, status=status, detail=detail,
                       max_depth=int(depth) if math.isfinite(depth) else None)


read_records = ldmrecords.by_config_id


class StageRunner:
    """Runs the stages of one advise into OUT/stages/NN-STAGE/ (through `launcher`: one
    process, local shards or a Slurm array; ldmadvise/launch.py) and keeps what they cost."""

    def __init__(self, launcher, out, question, assignments, metric, log):
        self.launcher, self.out, self.question = launcher, out, question
        self.assignments, self.metric, self.log = assignments, metric, log
        self.count = 0
        self.rows = {}      # (stage folder, config id) -> record row, for the report
        self.costs = []     # per stage: name, configurations, wall seconds of this call

    def _stage_folder(self, keys, precision, stage):
        self.count += 1
        folder = os.path.join(self.out, "stages", f"{self.count:02d}-{stage}")
        os.makedirs(folder, exist_ok=True)
        spec = sweep_file(self.question, [self.assignments[k] for k in keys], precision,
                          f"ldmbench advise, stage {stage}: {len(keys)} configurations at "
                          f"{precision['name']} precision")
        sweep_path = os.path.join(folder, "sweep.json")
        text = json.dumps(spec, indent=1) + "\n"
        if not os.path.exists(sweep_path) or open(sweep_path, encoding="utf-8").read() != text:
            with open(sweep_path + ".tmp", "w", encoding="utf-8") as f:
                f.write(text)
            os.replace(sweep_path + ".tmp", sweep_path)
        return folder, sweep_path

    def _launch(self, action, folder, sweep_path, keys, stage):
        """The launcher's plan or run of a stage, and the wall seconds it took here."""
        start = time.monotonic()
        try:
            result = action(folder, sweep_path, keys, stage, self.log)
        except LaunchError as e:
            raise MeasureError(str(e))
        return result, time.monotonic() - start

    def plan_stage(self, keys, stage="census"):
        """The memory plan of `keys` (census and storage, nothing built): its rows by key."""
        folder, sweep_path = self._stage_folder(keys, CENSUS, stage)
        path, seconds = self._launch(self.launcher.plan, folder, sweep_path, keys, stage)
        rows = read_records(path)
        self.costs.append({"stage": stage, "folder": folder, "records": path, "configurations": len(keys),
                           "keys": list(keys), "planned_only": True,
                           "precision": "memory plan (nothing built)", "wall_s_this_call": round(seconds, 2),
                           "wall_s_recorded": round(seconds, 2)})
        self.log({"event": "planned", "stage": stage, "folder": folder, "configurations": len(keys),
                  "refused": sum(rows[k].get("status") == "refused" for k in keys), "wall_s": round(seconds, 2)})
        return {k: rows[k] for k in keys}

    def recorded_s(self):
        """The stages' recorded seconds so far (what the report counts as recorded)."""
        return sum(c["wall_s_recorded"] or 0 for c in self.costs)

    def run_stage(self, keys, precision, stage):
        """The stage's measurements by key, its folder, its record rows and its records
        folder (STAGE/run, or STAGE/shards-N/merged when sharded)."""
        folder, sweep_path = self._stage_folder(keys, precision, stage)
        run, seconds = self._launch(self.launcher.run, folder, sweep_path, keys, stage)
        rows = read_records(os.path.join(run, "records.csv"))
        missing = [k for k in keys if k not in rows]
        if missing:
            raise MeasureError(f"stage {stage}: {run}/records.csv lacks {', '.join(missing)}")
        recorded = sum(number(rows[k], "wall_seconds") for k in keys)
        self.costs.append({"stage": stage, "folder": folder, "records": run, "configurations": len(keys),
                           "keys": list(keys), "precision": precision["name"],
                           "repetitions": precision.get("repetitions", 1), "wall_s_this_call": round(seconds, 2),
                           "wall_s_recorded": round(recorded, 2) if math.isfinite(recorded) else None})
        self.log({"event": "measured", "stage": stage, "folder": folder, "records": run,
                  "configurations": len(keys), "wall_s": round(seconds, 2)})
        for k in keys:
            self.rows[(folder, k)] = rows[k]
        return {k: measurement_of(rows[k], self.metric) for k in keys}, folder, rows, run
