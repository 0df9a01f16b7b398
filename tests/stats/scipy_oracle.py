#!/usr/bin/env python3
"""SciPy's answers to the cases tests/stats/stats_test.cpp sends (JSON on stdin, JSON on
stdout): the independent oracle of harness/stats (order-statistic median intervals, t
intervals on logs, Welch and paired t tests on logs, non-central t power)."""
import json
import math
import sys
import warnings

import numpy as np
from scipy import stats


def median_rank(n, confidence):
    # largest l with 1 - 2 P(B <= l - 1) >= confidence, B ~ Binomial(n, 1/2); coverage
    # falls as l grows, so it is the count of the l that reach it
    l = np.arange(1, (n + 1) // 2 + 1)
    return int(np.sum(1 - 2 * stats.binom.cdf(l - 1, n, 0.5) >= confidence))


def answer(case):
    kind = case["kind"]
    if kind == "median_rank":
        return {"rank": median_rank(case["n"], case["confidence"]),
                "coverage": 1 - 2 * stats.binom.cdf(max(median_rank(case["n"], case["confidence"]), 1) - 1,
                                                    case["n"], 0.5)}
    if kind == "log_t_interval":
        logs = np.log(case["values"])
        k = len(logs)
        half = stats.t.ppf(0.5 + case["confidence"] / 2, k - 1) * logs.std(ddof=1) / math.sqrt(k)
        return {"low": math.exp(logs.mean() - half), "high": math.exp(logs.mean() + half)}
    if kind == "welch":
        r = stats.ttest_ind(np.log(case["b"]), np.log(case["a"]), equal_var=False)
        return {"statistic": float(r.statistic), "p": float(r.pvalue)}
    if kind == "paired":
        r = stats.ttest_rel(np.log(case["b"]), np.log(case["a"]))
        return {"statistic": float(r.statistic), "p": float(r.pvalue)}
    if kind == "power":
        # the rejection probability of a two-sided t test at the given non-centrality
        df, alpha, ncp = case["df"], case["alpha"], case["ncp"]
        if df is None:
            c = stats.norm.ppf(1 - alpha / 2)
            return {"power": float(stats.norm.sf(c - ncp) + stats.norm.cdf(-c - ncp))}
        c = stats.t.ppf(1 - alpha / 2, df)
        return {"power": float(stats.nct.sf(c, df, ncp) + stats.nct.cdf(-c, df, ncp))}
    raise ValueError(kind)


# SciPy's non-central t warns on far tails (and clips them to 0 or 1, which is right).
warnings.simplefilter("ignore", RuntimeWarning)
print(json.dumps([answer(c) for c in json.load(sys.stdin)]))
