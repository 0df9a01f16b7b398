"""The advise report: summary.md (the answer, how sure, the front, what was pruned and why,
the time spent) and front.png (every configuration measured, at its last precision, the
time/error front, the budgets and the recommendation marked)."""
import os

from .search import pareto_front


def fmt_bytes(b):
    return f"{b / 2**20:.4g} MiB"


def counts_of(costs, space):
    """The counts every output of an advise says (the console's last line, summary.md,
    result.json), from its stages' costs alone: one source, so they cannot disagree.
    planned: configurations the census planned (nothing built); measured: stage
    measurements (a configuration measured at two levels counts twice); configurations:
    the distinct configurations measured; stages: the stages that measured (the census
    plans, it is not one of them); census_stages: the census's (0 or 1)."""
    measuring = [c for c in costs if not c.get("planned_only")]
    planning = [c for c in costs if c.get("planned_only")]
    distinct = set()
    for c in measuring:
        distinct.update(c.get("keys", ()))
    return {"space": space, "planned": sum(c["configurations"] for c in planning),
            "census_stages": len(planning), "measured": sum(c["configurations"] for c in measuring),
            "configurations": len(distinct), "stages": len(measuring),
            "wall_s_recorded": round(sum(c["wall_s_recorded"] or 0 for c in costs), 2)}


def plural(n, word, words=None):
    return f"{n} {word if n == 1 else (words or word + 's')}"


def counts_sentence(counts):
    """The one sentence of the counts, word for word the same on the console and in summary.md."""
    planned = (f"The census planned {plural(counts['planned'], 'configuration')} of the space without building "
               "them; " if counts["census_stages"] else "")
    return (f"{planned}{plural(counts['configurations'], 'configuration')} of {counts['space']} measured, "
            f"{plural(counts['measured'], 'measurement')} in {plural(counts['stages'], 'measuring stage')} "
            "(a configuration measured at two precisions counts twice); "
            f"recorded wall time {counts['wall_s_recorded']:.1f} s")


def write_front_plot(path, goal, measured, front, recommended, metric, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, (m, pruned) in measured.items():
        err = [[m.time - m.time_low], [m.time_high - m.time]]
        style = dict(color="0.65", marker="x") if pruned else dict(color="tab:blue", marker="o")
        ax.errorbar([m.time], [m.error], xerr=err, yerr=[[min(m.error_band, m.error * 0.999)], [m.error_band]],
                    linestyle="none", markersize=5, elinewidth=0.7, **style)
    fm = [measured[k][0] for k in front]
    if fm:
        ax.plot([m.time for m in fm], [m.error for m in fm], "-", color="tab:orange", label="front (time, error)")
    if recommended and recommended in measured:
        m = measured[recommended][0]
        ax.plot([m.time], [m.error], marker="*", markersize=18, color="tab:red", linestyle="none",
                label=f"recommended: {recommended}")
    if goal.budget_ms is not None:
        ax.axvline(goal.budget_ms, color="tab:red", linestyle=":", label=f"budget {goal.budget_ms} ms")
    if goal.max_error is not None:
        ax.axhline(goal.max_error, color="tab:purple", linestyle=":", label=f"error bound {goal.max_error}")
    ax.set_xlabel("frame time, ms (median, 95 % interval)")
    ax.set_ylabel("MSE vs reference (band: its noise)" if metric == "mse" else "1 - MSSIM")
    ax.set_yscale("log")
    ax.set_xscale("log")
    ax.plot([], [], "x", color="0.65", label="pruned (last measurement)")
    ax.plot([], [], "o", color="tab:blue", label="kept to the end")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def write_report(out, result, search, goal, metric, costs, title):
    """summary.md and front.png in OUT/report/; returns the folder."""
    folder = os.path.join(out, "report")
    os.makedirs(folder, exist_ok=True)
    measured = {k: (s.measurement, s.pruned) for k, s in search.states.items() if s.measurement is not None}
    # Memory is exact, so its budget is a hard filter: the front is the time/error trade-off
    # among the configurations that fit it.
    ok = {k: m for k, (m, _) in measured.items() if m.status == "ok" and goal.memory_fits(m)}
    front = pareto_front(goal, ok)
    rec = result.get("recommended")
    write_front_plot(os.path.join(folder, "front.png"), goal, {k: measured[k] for k in ok}, front,
                     rec, metric, title)
    lines = [f"# {title}", ""]
    lines += result["answer_lines"] + [""]
    lines += ["![front](front.png)", "",
              "## Front found", "",
              f"The front: {plural(len(front), 'configuration')} of the {len(ok)} measured without loss"
              + (" within the memory budget" if goal.budget_bytes is not None else "") + ", the others "
              "slower or with more error than one of these; each at its last precision "
              "(time: median and 95 % interval; error: value and the reference's noise band):", "",
              "| configuration | frame ms [interval] | error ± band | memory | precision |",
              "|---|---|---|---|---|"]
    for k in front:
        m = ok[k]
        lines.append(f"| {k}{' **(recommended)**' if k == rec else ''} | {m.time:.4g} [{m.time_low:.4g}, "
                     f"{m.time_high:.4g}] | {m.error:.4g} ± {m.error_band:.2g} | {fmt_bytes(m.memory)} | "
                     f"{'verify' if m.level >= 3 else f'level {m.level}'} |")
    lines += ["", "## Pruned, and why", "",
              "| configuration | stage | why |", "|---|---|---|"]
    for k, s in sorted(search.states.items(), key=lambda kv: (kv[1].stage, kv[0])):
        if s.pruned:
            lines.append(f"| {k} | {s.stage} | {s.pruned} |")
    counts = {}
    for s in search.states.values():
        if s.pruned:
            kind = s.pruned.split(":")[0].split(" (")[0]
            counts[kind] = counts.get(kind, 0) + 1
    lines += ["", "By reason: " + ", ".join(f"{v} {k}" for k, v in sorted(counts.items())) + ".",
              "", "## Time spent", "",
              "| stage | configurations | precision | wall s (this call) | wall s (recorded) |", "|---|---|---|---|---|"]
    for c in costs:
        lines.append(f"| {c['stage']} | {c['configurations']} | {c['precision']} | {c['wall_s_this_call']} | "
                     f"{c['wall_s_recorded']} |")
    lines += ["", counts_sentence(result["counts"]) + ".", ""]
    with open(os.path.join(folder, "summary.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    return folder
