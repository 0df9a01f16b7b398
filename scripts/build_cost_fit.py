#!/usr/bin/env python3
"""Build time against fragments, per structure: the fixed part and the part per fragment.

    scripts/build_cost_fit.py RECORDS_CSV

Least-squares lines through (fragments, median) of the ok records of each structure (one
scene, one N, several R_LDM), for the build, for the empty raster pass (raster_baseline: the
geometry pass with nothing shaded), for the census shader's pass (raster_touch: every
fragment shaded, one atomicAdd) and for the build less the latter. Issue 21 asked what the
fixed per-build cost is: when the build's intercept is about raster_baseline's, it is the
per-triangle work of rasterising the scene into the N views, which every renderer of these
views pays, and the build less it is close to proportional to the fragments.
"""
import sys

import numpy as np
import pandas as pd
import ldmrecords


def fit(x, y):
    slope, intercept = np.polyfit(x, y, 1)
    return intercept, slope * 1e6  # ms, ns per fragment


def main(path):
    records = ldmrecords.dataframe(path)
    records = records[records["status"] == "ok"]
    rows = []
    for structure, group in records.groupby("structure", sort=False):
        if group["fragments"].nunique() < 2:
            continue
        build = group["build_ms_median"]
        raster = group["raster_baseline_ms_median"]
        touch = group["raster_touch_ms_median"]
        row = {"structure": structure, "points": len(group)}
        for name, values in (("build", build), ("raster_baseline", raster), ("raster_touch", touch),
                             ("build_minus_touch", build - touch)):
            intercept, slope = fit(group["fragments"], values)
            row[f"{name}_intercept_ms"] = round(intercept, 1)
            row[f"{name}_ns_per_fragment"] = round(slope, 1)
        row["intercept_share_of_smallest_build_%"] = round(
            100 * row["build_intercept_ms"] / build.min(), 0)
        rows.append(row)
    print(pd.DataFrame(rows).to_string(index=False))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
