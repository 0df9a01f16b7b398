#!/usr/bin/env python3
"""Coverage of other widening forms, from the records of a pooled coverage run (docs/timing.md,
"Coverage", 2026-12-05): each record's repetitions' own variance is recovered from its
interval as the pooled form widened it (a build of that day pooled the t interval of
--isolation process repetitions with the calibration's variance; the form was measured and
rejected), and the intervals of the unpooled form (the one ldmbench writes), the pooled
form, the pooled form unless an F test rejects pooling, and the wider of the two are
judged against the other run's median.

  scripts/timing_coverage_forms.py DIR    (DIR/first/records.csv, DIR/second/records.csv)
"""
import csv, math, re, sys, statistics
from scipy import stats
z = 1.959963984540054
def rows(p): return {r['config_id']: r for r in csv.DictReader(open(p))}
a, b = rows(sys.argv[1] + '/first/records.csv'), rows(sys.argv[1] + '/second/records.csv')
def nu_of(r):
    m = re.search(r'from (\d+) processes', r['time_calibration'])
    return int(m.group(1)) - 1
def recover(r, sub):
    S = float(r['time_run_to_run_spread']); K = int(r['repetitions']); nu = nu_of(r)
    med = float(r[sub + '_ms_median']); low = float(r[sub + '_ms_ci_low']); high = float(r[sub + '_ms_ci_high'])
    h = max(math.log(med / low), math.log(high / med))
    bpart = z * S / math.sqrt(2 * K)
    wp = math.sqrt(max(h * h - bpart * bpart, 0))
    t = stats.t.ppf(0.975, nu + K - 1)
    v = ((wp / t) ** 2 * K * (nu + K - 1) - nu * S * S / 2) / (K - 1)
    return S, K, nu, med, max(v, 0), bpart
def forms(S, K, nu, v, bpart):
    own = stats.t.ppf(0.975, K - 1) * math.sqrt(v / K)
    pooled = stats.t.ppf(0.975, nu + K - 1) * math.sqrt(((K - 1) * v + nu * S * S / 2) / (nu + K - 1) / K)
    F = v / (S * S / 2); Fcrit = stats.f.ppf(0.95, K - 1, nu)
    ftest = pooled if F <= Fcrit else own
    known = z * math.sqrt(S * S / 2 / K)
    return {'unpooled': math.hypot(own, bpart), 'pooled': math.hypot(pooled, bpart),
            'pooled_unless_F': math.hypot(ftest, bpart), 'max(pooled,own)': math.hypot(max(pooled, own), bpart)}
for sub in ['build', 'pass', 'frame']:
    for name, x, y in (('first', a, b), ('second', b, a)):
        hits = {}; widths = {}; ratios = []
        for k in x:
            if k not in y: continue
            S, K, nu, med, v, bp = recover(x[k], sub)
            m2 = float(y[k][sub + '_ms_median'])
            ratios.append(math.log(m2 / med))
            for f, h in forms(S, K, nu, v, bp).items():
                hits[f] = hits.get(f, 0) + (abs(math.log(m2 / med)) <= h)
                widths.setdefault(f, []).append(h)
        rms = math.sqrt(sum(r * r for r in ratios) / len(ratios))
        print(sub, name, 'n', len(ratios), 'rms', round(rms, 3), ' '.join(f"{f}:{hits[f]}/{len(ratios)} w{statistics.median(widths[f]):.3f}({statistics.median(widths[f])/rms:.2f}x)" for f in hits))
