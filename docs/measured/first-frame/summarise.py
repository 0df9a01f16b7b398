#!/usr/bin/env python3
"""Summarise measure.sh's runs: per structure and side, the first frame's time over the
median steady frame (frames 1..), the steady median, and the wall time; OLD/NEW ratios pair
by pair, quoted as median (min-max)."""
import csv, os, statistics, sys

out = sys.argv[1]
walls = {}
for line in open(os.path.join(out, "wall.txt")):
    side, i, secs = line.split()
    walls[(side, int(i))] = float(secs)

def frames(run_dir):
    recs = list(csv.DictReader(open(os.path.join(run_dir, "records.csv"))))
    result = {}
    for r in recs:
        rows = list(csv.DictReader(open(os.path.join(run_dir, r["frame_samples_csv"]))))
        per = {}
        for row in rows:
            if row["subpass"] == "frame":
                per[int(row["frame"])] = float(row["ms"])
        first = per[0]
        steady = statistics.median(v for k, v in per.items() if k > 0)
        result[r["structure"]] = dict(first=first, steady=steady,
                                      rebuilds=r["sizing_rebuilds"], status=r["status"],
                                      wall=float(r["wall_seconds"]))
    return result

def spread(values, fmt="{:.3g}"):
    return (fmt + " (" + fmt + "-" + fmt + ")").format(statistics.median(values), min(values), max(values))

pairs = sorted({i for _, i in walls})
data = {(s, i): frames(os.path.join(out, f"{s}-{i}")) for s in ("old", "new") for i in pairs}
structures = sorted(data[("old", pairs[0])])
print(f"{len(pairs)} pairs, OLD and NEW in turn; median (min-max) over the pairs")
print("| structure | side | first frame ms | steady frame ms | first / steady | rebuilds | status | record wall s |")
print("| --- | --- | ---: | ---: | ---: | ---: | --- | ---: |")
for st in structures:
    for side in ("old", "new"):
        d = [data[(side, i)][st] for i in pairs]
        print(f"| {st} | {side} | {spread([x['first'] for x in d])} | {spread([x['steady'] for x in d])} | "
              f"{spread([x['first'] / x['steady'] for x in d], '{:.2f}')} | "
              f"{','.join(str(x['rebuilds']) for x in d)} | {','.join(sorted({x['status'] for x in d}))} | "
              f"{spread([x['wall'] for x in d])} |")
print()
print("OLD / NEW ratios, pair by pair:")
for st in structures:
    fr = [data[("old", i)][st]["first"] / data[("new", i)][st]["first"] for i in pairs]
    sr = [data[("old", i)][st]["steady"] / data[("new", i)][st]["steady"] for i in pairs]
    wr = [data[("old", i)][st]["wall"] / data[("new", i)][st]["wall"] for i in pairs]
    print(f"- {st}: first frame {spread(fr, '{:.2f}')}, steady frame {spread(sr, '{:.2f}')}, "
          f"record wall time {spread(wr, '{:.2f}')}")
wr = [walls[("old", i)] / walls[("new", i)] for i in pairs]
print(f"- whole process: OLD {spread([walls[('old', i)] for i in pairs])} s, "
      f"NEW {spread([walls[('new', i)] for i in pairs])} s, ratio {spread(wr, '{:.2f}')}")
