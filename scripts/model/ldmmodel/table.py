"""The fits and predictions as plain-text tables."""
import numpy as np

from . import model


def pct(x):
    return "—" if x is None else f"{100 * x:.1f} %"


def num(x):
    return "—" if x is None else f"{x:.4g}"


def short_name(column, subpass):
    prefix = "work_" + subpass + "_"
    return column[len(prefix):] if subpass != "frame" and column.startswith(prefix) else column


def render(rows, align):
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    out = []
    for k, r in enumerate(rows):
        cells = [c.rjust(w) if a == "r" else c.ljust(w) for c, w, a in zip(r, widths, align)]
        out.append("  " + "  ".join(cells).rstrip())
        if k == 0:
            out.append("  " + "  ".join("-" * w for w in widths))
    return "\n".join(out)


def fit_table(f, by=()):
    """One fit: its heading (records, R², held-out error) and its coefficients with units,
    each with its mean share of the fitted time; then the counters dropped, and why."""
    head = (f"{model.describe_group(f['group'], by)} · {f['subpass']} ({f['time_column']}): "
            f"{f['records']} records, {f['configurations']} configurations; R² {num(f['r2'])}, "
            f"held-out median error {pct(f['heldout_median_error'])} "
            f"(p90 {pct(f['heldout_p90_error'])}, {f['folds']}-fold by configuration)")
    measured = np.array(f["measured_ms"]) * 1e6
    if f.get("repeat_spread") is not None:
        head += (f"\n  noise floor: a record lies {pct(f['repeat_spread'])} (median) from the median of its "
                 "configuration's other records (equal counters: no model of them predicts it better)")
    rows = [["counter", "coefficient", "unit", "share of time"]]
    mean_t = float(np.mean(measured))
    if f.get("intercept", True):
        rows.append(["(fixed cost)", f"{f['intercept_ns']:.4g}", "ns per frame",
                     f"{100 * f['intercept_ns'] / mean_t:.1f} %" if mean_t > 0 else "—"])
    for name, c in sorted(f["coefficients_ns"].items(), key=lambda kv: -kv[1] * f.get("mean_counts", {}).get(kv[0], 0)):
        share = c * f.get("mean_counts", {}).get(name, 0) / mean_t if mean_t > 0 else None
        rows.append([short_name(name, f["subpass"]), f"{c:.4g}", f"ns per {f['units'][name]}",
                     "—" if share is None else f"{100 * share:.1f} %"])
    text = [head, render(rows, "lrlr")]
    kinds = f.get("structures", [])
    if len(set(kinds)) > 1 and all(v is not None for v in f["heldout_ms"]):
        parts = []
        for k in sorted(set(kinds)):
            pairs = [(h, m) for h, m, s in zip(f["heldout_ms"], f["measured_ms"], kinds) if s == k]
            err = np.median([abs(h - m) / m for h, m in pairs])
            bias = np.median([(h - m) / m for h, m in pairs])
            parts.append(f"{k} {100 * err:.0f} % ({100 * bias:+.0f} %)")
        text.append("  held-out median error (and median signed error) by structure: " + ", ".join(parts))
    if f["dropped"]:
        text.append("  dropped: " + "; ".join(f"{short_name(d['column'], f['subpass'])} ({d['reason']})"
                                              for d in f["dropped"]))
    if f.get("left_out_zero_time"):
        text.append(f"  left out: {f['left_out_zero_time']} record(s) whose {f['time_column']} is 0 or absent")
    return "\n".join(text)


def summary_table(document):
    by = document.get("by", [])
    rows = [["device · sub-pass", "records", "R²", "held-out median error", "p90", "noise floor"]]
    for f in document["fits"]:
        rows.append([f"{model.describe_group(f['group'], by)} · {f['subpass']}", str(f["records"]), num(f["r2"]),
                     pct(f["heldout_median_error"]), pct(f["heldout_p90_error"]), pct(f.get("repeat_spread"))])
    return render(rows, "lrrrrr")


def prediction_table(f, lines, missing, by=()):
    """Predicted against measured time per configuration, and the median relative error."""
    rows = [["configuration", "predicted ms", "measured ms", "error"]]
    errors = []
    for config_id, p, m in lines:
        e = abs(p - m) / m if m is not None and m > 0 else None
        if e is not None:
            errors.append(e)
        rows.append([config_id, f"{p:.4g}", num(m), pct(e)])
    head = f"{model.describe_group(f['group'], by)} · {f['subpass']}: {len(lines)} configurations"
    if errors:
        head += f"; median error {pct(float(np.median(errors)))} over {len(errors)} measured on this device"
    else:
        head += "; none measured on this device (predictions only)"
    text = [head, render(rows, "lrrr")]
    if missing:
        text.append("  warning: the run has no column of " + ", ".join(missing) +
                    " (counted 0: a build without these counters; its predictions are low)")
    return "\n".join(text)
