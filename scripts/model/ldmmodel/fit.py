"""The cost model: time ≈ c₀ + Σ cᵢ · counterᵢ with every cᵢ ≥ 0 (non-negative least squares,
scipy.optimize.nnls), features scaled first, constant and collinear counters dropped (and
named), and held-out errors from k-fold cross-validation in which a configuration's records
are never split between training and test.

Times enter in ns (records hold ms), so a coefficient is "ns per <unit>" and the intercept
"ns per frame" (the sub-pass's fixed cost). Rows are weighted by 1 / measured time by
default, which minimises the squared *relative* error — what the held-out error measures —
rather than letting the largest configurations decide every coefficient.
"""
import math

import numpy as np
from scipy.optimize import nnls

NS_PER_MS = 1e6
INTERCEPT = "(fixed)"
COLLINEAR_TOLERANCE = 1e-8  # relative residual of a counter explained by those kept before it


class FitError(Exception):
    """Nothing to fit: the message says why."""


def drop_uninformative(X, names, intercept):
    """Columns to keep, and (name, reason) for those dropped: all-zero, constant (the
    intercept's), or a linear combination of the counters kept before them."""
    kept, dropped = [], []
    n = X.shape[0]
    basis = [np.ones(n)] if intercept else []
    basis_names = [INTERCEPT] if intercept else []
    for j, name in enumerate(names):
        col = X[:, j]
        if not np.any(col):
            dropped.append((name, "all zero"))
            continue
        if intercept and np.all(col == col[0]):
            dropped.append((name, "constant (the fixed cost's)"))
            continue
        scale = np.max(np.abs(col))
        if basis:
            B = np.column_stack([b / (np.max(np.abs(b)) or 1.0) for b in basis])
            beta, *_ = np.linalg.lstsq(B, col / scale, rcond=None)
            residual = col / scale - B @ beta
            if np.linalg.norm(residual) <= COLLINEAR_TOLERANCE * max(np.linalg.norm(col / scale), 1e-300):
                # express it in the kept counters' own units
                terms = []
                for k, b in enumerate(beta):
                    bk = b * scale / (np.max(np.abs(basis[k])) or 1.0)
                    if abs(b) > 1e-9:
                        sign = "-" if bk < 0 else "+"
                        terms.append(f"{sign} {abs(bk):.4g}·{basis_names[k]}")
                expression = " ".join(terms)
                expression = expression[2:] if expression.startswith("+ ") else "-" + expression[2:]
                dropped.append((name, "collinear: = " + expression if terms else "collinear"))
                continue
        kept.append(j)
        basis.append(col)
        basis_names.append(name)
    return kept, dropped


def solve(X, y, intercept, relative):
    """(intercept, coefficients) in y's units per counter unit, all ≥ 0."""
    A = np.column_stack([np.ones(len(y))] + [X[:, j] for j in range(X.shape[1])]) if intercept else X.copy()
    if A.shape[1] == 0:
        return 0.0, np.zeros(0)
    scale = np.max(np.abs(A), axis=0)
    scale[scale == 0] = 1.0
    As = A / scale
    w = 1.0 / y if relative else np.ones_like(y) / (np.max(np.abs(y)) or 1.0)
    x, _ = nnls(As * w[:, None], y * w, maxiter=50 * As.shape[1] + 500)
    x = x / scale
    return (float(x[0]), x[1:]) if intercept else (0.0, x)


def predict(X, c0, c):
    return c0 + X @ c


def r_squared(y, p):
    ss_tot = float(np.sum((y - np.mean(y)) ** 2))
    ss_res = float(np.sum((y - p) ** 2))
    return 1.0 - ss_res / ss_tot if ss_tot > 0 else (1.0 if ss_res == 0 else float("nan"))


def folds_of(groups, k, seed=0):
    """A fold per row: the distinct groups (configurations) shuffled with a fixed seed and
    dealt round-robin into k folds, so a group's rows share a fold."""
    distinct = sorted(set(groups))
    order = np.random.RandomState(seed).permutation(len(distinct))
    fold_of_group = {distinct[i]: rank % k for rank, i in enumerate(order)}
    return np.array([fold_of_group[g] for g in groups])


def cross_validate(X, y, groups, k, intercept, relative):
    """Held-out predictions of every row (NaN where it could not be held out), and the k used."""
    n_groups = len(set(groups))
    k = min(k, n_groups)
    held = np.full(len(y), np.nan)
    if k < 2:
        return held, k
    fold = folds_of(groups, k)
    for f in range(k):
        test = fold == f
        c0, c = solve(X[~test], y[~test], intercept, relative)
        held[test] = predict(X[test], c0, c)
    return held, k


def fit(X, y_ms, names, groups, folds=5, intercept=True, relative=True):
    """A fit of y_ms (rows of records) on the counters X (columns `names`). Returns a dict:
    intercept_ns, coefficients_ns {name: ns per unit} (kept counters only), dropped
    [(name, reason)], r2, heldout (median, p90 relative error, R²), folds, and the rows'
    in-sample and held-out predictions in ms."""
    X = np.asarray(X, dtype=float)
    y_ms = np.asarray(y_ms, dtype=float)
    if len(y_ms) < 2:
        raise FitError(f"{len(y_ms)} record(s): at least 2 are needed")
    y = y_ms * NS_PER_MS
    kept, dropped = drop_uninformative(X, names, intercept)
    Xk = X[:, kept]
    c0, c = solve(Xk, y, intercept, relative)
    p = predict(Xk, c0, c)
    held, k = cross_validate(Xk, y, groups, folds, intercept, relative)
    ok = ~np.isnan(held)
    rel = np.abs(held[ok] - y[ok]) / y[ok]
    # Records of one configuration (several runs): each against the median of the others.
    # Their counters are equal, so no model of the counters can predict a held-out record
    # better than its configuration's other records do: the noise floor of the held-out error.
    by_group = {}
    for g, t in zip(groups, y):
        by_group.setdefault(g, []).append(t)
    spread = [abs(t - np.median(ts[:i] + ts[i + 1:])) / t
              for ts in by_group.values() if len(ts) > 1 for i, t in enumerate(ts)]
    return {
        "intercept_ns": c0,
        "coefficients_ns": {names[j]: float(c[i]) for i, j in enumerate(kept)},
        "dropped": [{"column": n, "reason": r} for n, r in dropped],
        "r2": r_squared(y, p),
        "in_sample_median_error": float(np.median(np.abs(p - y) / y)),
        "heldout_median_error": float(np.median(rel)) if rel.size else None,
        "heldout_p90_error": float(np.percentile(rel, 90)) if rel.size else None,
        "heldout_r2": r_squared(y[ok], held[ok]) if rel.size > 1 else None,
        "folds": k,
        "repeat_spread": float(np.median(spread)) if spread else None,
        "predicted_ms": (p / NS_PER_MS).tolist(),
        "heldout_ms": [None if math.isnan(v) else v / NS_PER_MS for v in held],
    }
