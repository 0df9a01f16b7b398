#!/usr/bin/env python3
"""What runs cost beside their measured frames (issue 21), from their run folders alone.

    scripts/harness_cost.py LABEL=RUN_DIR[:WALL_SECONDS] ...

For each run: the measured frames' timed work (every timed sub-pass of every measured frame,
summed from the samples files, so that runs of builds older than the frames_timed_ms column
read alike), the build checks' wall time (verify_ms, verify_warmup_ms where recorded), and,
given the process's wall seconds (e.g. from /usr/bin/time), the ratio wall / timed.
A second table compares the frame and build medians of the configurations both runs of a
pair measured: whether each median of the second lies within the first's 95% interval.
"""
import sys
from pathlib import Path

import pandas as pd
import ldmrecords

# A frame's timed work: its "frame" sum (every sub-pass but the baselines) and the baselines.
TIMED = {"frame", "raster_baseline", "raster_touch"}


def timed_ms(run: Path, records: pd.DataFrame) -> float:
    total = 0.0
    for name in records["frame_samples_csv"].dropna():
        samples = pd.read_csv(run / name)
        total += samples.loc[samples["subpass"].isin(TIMED), "ms"].sum()
    return total


def main(argv):
    if not argv:
        sys.exit(__doc__)
    rows, runs = [], {}
    for arg in argv:
        label, _, rest = arg.partition("=")
        path, _, wall = rest.partition(":")
        run = Path(path)
        records = ldmrecords.dataframe(run)
        runs[label] = records.set_index("config_id")
        timed = timed_ms(run, records) / 1000
        verify = records.get("verify_ms", pd.Series(dtype=float)).sum() / 1000
        verify_warmup = records.get("verify_warmup_ms", pd.Series(dtype=float)).sum() / 1000
        row = {"run": label, "configurations": len(records), "measured_frames_s": round(timed, 3),
               "verify_measured_s": round(verify, 3), "verify_warmup_s": round(verify_warmup, 3),
               "verify_share_%": round(100 * verify / timed, 2) if timed else None}
        if wall:
            row["wall_s"] = float(wall)
            row["wall_over_measured"] = round(float(wall) / timed, 3)
        rows.append(row)
    print(pd.DataFrame(rows).to_string(index=False))
    labels = list(runs)
    for a, b in zip(labels[::2], labels[1::2]):
        both = runs[a].index.intersection(runs[b].index)
        inside = {}
        for column in ("frame", "build"):
            lo, hi, med = (f"{column}_ms_ci_low", f"{column}_ms_ci_high", f"{column}_ms_median")
            within = (runs[b].loc[both, med] >= runs[a].loc[both, lo]) & (runs[b].loc[both, med] <= runs[a].loc[both, hi])
            inside[column] = f"{int(within.sum())}/{len(both)}"
        print(f"{b} medians within {a}'s 95% intervals: frame {inside['frame']}, build {inside['build']}")


if __name__ == "__main__":
    main(sys.argv[1:])
