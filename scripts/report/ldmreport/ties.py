"""What the report may call a difference, and what it must call a tie.

A ranking or a Pareto front that picks a winner by a difference below the measurement's
uncertainty is noise presented as a finding. Each criterion has its own band:
  time    two medians tie when their 95 % intervals (`<subpass>_ms_ci_low/high`, the
          record's own: order statistics of the frames, or t over the repetitions) overlap;
          records without intervals (older runs) tie only when equal.
  error   two MSEs tie when they differ by no more than the larger reference noise floor
          (`ref_noise_mse`: the reference's own expected MSE) or by float summation order
          (a relative 1e-6: the same image summed in another order); two MSSIMs when they
          differ by no more than a quarter of the reference halves' own SSIM deficit
          (1 - ref_noise_mssim, the same scale the MSE floor takes from its halves) or 1e-6.
  memory  bytes are exact: ties only when equal.
A best is then every record tied with the best one, and the Pareto front every record that
no other record beats beyond the bands in one criterion while being no worse in the other.
"""
import math

FLOAT_ORDER = 1e-6  # relative: the same sum in another order


def _finite(x):
    return x is not None and isinstance(x, (int, float)) and math.isfinite(x)


class Measure:
    """One record's value of a criterion with its tie band: `low`/`high` for an interval
    (time), `band` for a symmetric tolerance (errors, at least float summation order), or
    `exact` (memory)."""

    def __init__(self, value, low=None, high=None, band=0.0, exact=False):
        self.value, self.band, self.exact = value, band, exact
        self.low = low if _finite(low) else None
        self.high = high if _finite(high) else None


def tied(a, b):
    """Whether two Measures of one criterion cannot be told apart."""
    if a.value == b.value:
        return True
    if a.exact or b.exact or not (_finite(a.value) and _finite(b.value)):
        return False
    if a.low is not None and a.high is not None and b.low is not None and b.high is not None:
        return a.low <= b.high and b.low <= a.high
    tolerance = max(a.band, b.band, FLOAT_ORDER * max(abs(a.value), abs(b.value)))
    return abs(a.value - b.value) <= tolerance


def better(a, b, higher_is_better):
    """a beats b beyond the tie band."""
    if tied(a, b):
        return False
    return a.value > b.value if higher_is_better else a.value < b.value


def best_and_tied(measures, higher_is_better):
    """Indices (into `measures`) of the best record and of every record tied with it, the
    best first; empty for no measures."""
    if not measures:
        return []
    order = sorted(range(len(measures)), key=lambda i: measures[i].value, reverse=higher_is_better)
    best = order[0]
    return [best] + [i for i in order[1:] if tied(measures[i], measures[best])]


def dominates(xj, yj, xi, yi, y_higher_is_better):
    """Record j dominates record i: no worse in time (x, lower is better) and in the metric
    (y), and better beyond the tie band in at least one of them."""
    no_worse = not better(xi, xj, False) and not better(yi, yj, y_higher_is_better)
    return no_worse and (better(xj, xi, False) or better(yj, yi, y_higher_is_better))


def pareto_front(xs, ys, y_higher_is_better):
    """Indices of the records no other record dominates, in order of time: ties beyond
    which nothing is better all stay on the front."""
    front = [i for i in range(len(xs))
             if not any(dominates(xs[j], ys[j], xs[i], ys[i], y_higher_is_better)
                        for j in range(len(xs)) if j != i)]
    return sorted(front, key=lambda i: xs[i].value)


def time_measure(table, row, subpass):
    """The record's median of `subpass` with its interval (query: the pass's own sum)."""
    median = table.num(f"{subpass}_ms_median")[row]
    return Measure(median, table.num(f"{subpass}_ms_ci_low")[row], table.num(f"{subpass}_ms_ci_high")[row])


def error_measure(table, row, column, prefix, metric):
    """An MSE or MSSIM with its tie band from the reference it was scored against."""
    value = table.num(column)[row]
    noise_prefix = f"{prefix}_" if prefix else ""
    if metric == "mse":
        band = table.num(f"{noise_prefix}ref_noise_mse")[row]
    else:
        band = (1 - table.num(f"{noise_prefix}ref_noise_mssim")[row]) / 4
    return Measure(value, band=band if _finite(band) and band >= 0 else 0.0)


def exact_measure(value):
    return Measure(value, exact=True)


def dominates_all(a, b, higher_is_better):
    """Record a dominates record b over several criteria (lists of Measures, one flag per
    criterion): a is no worse in any beyond the tie bands and better in at least one."""
    pairs = list(zip(a, b, higher_is_better))
    no_worse = not any(better(y, x, h) for x, y, h in pairs)
    return no_worse and any(better(x, y, h) for x, y, h in pairs)


def pareto_front_all(points, higher_is_better):
    """Indices of the points (lists of Measures) that no other point dominates over every
    criterion, in order of the first criterion: ties beyond which nothing is better all stay."""
    front = [i for i in range(len(points))
             if not any(dominates_all(points[j], points[i], higher_is_better)
                        for j in range(len(points)) if j != i)]
    return sorted(front, key=lambda i: points[i][0].value)


def tied_in_all(a, b):
    """Two records no criterion tells apart."""
    return all(tied(x, y) for x, y in zip(a, b))
