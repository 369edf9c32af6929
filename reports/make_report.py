#!/usr/bin/python3
"""Turns the sweep of `rayint bench` (reports/bench.json) into the accuracy/cost report:

  reports/error_vs_time.png  error against time per ray, one line per method (log-log)
  reports/error_vs_knob.png  error against each method's knob, with fitted convergence orders
  reports/README.md          the Pareto front in words and the 1e-3 / 1e-6 / 1e-10 target tables

Every number comes from the one JSON file; in particular the "cheapest setting per target" rows
are the ones `rayint bench` computed (src/rayint/studies/sweep.cpp, tested in
tests/test_sweep.cpp) -- this script formats them, it does not re-derive them.

Run with Debian's python3-matplotlib: /usr/bin/python3 reports/make_report.py [bench.json]
(scripts/report.sh builds, runs the sweep and then this).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Errors of exactly 0 cannot sit on a log axis; they are drawn at this floor, marked as such.
ZERO_FLOOR = 1e-18
# Convergence-order fits use the points whose error lies in this window (see fit_order).
FIT_LOW, FIT_HIGH = 1e-12, 1e-2
# The case used for a clean convergence study (cases/README.md: "for convergence-order studies").
SMOOTH_CASE = "smooth-convergence"
KNOB_TITLES = {
    "n": "steps per segment n",
    "rtol": "1 / rtol",
    "size": "table size",
}
COLOURS = {
    "riemann": "tab:blue", "rk4": "tab:orange", "ode": "tab:green",
    "preintegrated": "tab:red", "psi_table": "tab:purple",
    "nerf": "darkred", "pl_nerf": "navy",
    "exact": "black", "paper": "tab:gray", "eq5": "tab:brown", "eq6": "tab:pink",
    "eq7": "tab:olive", "eq8": "tab:cyan", "particle": "gold",
}


def fmt_time(s):
    if s is None or s <= 0:
        return "n/a"
    if s >= 1e-3:
        return f"{s * 1e3:.3g} ms"
    if s >= 1e-6:
        return f"{s * 1e6:.3g} us"
    return f"{s * 1e9:.3g} ns"


def fmt_err(e):
    if e is None:
        return "non-finite"
    if e == 0:
        return "0"
    return f"{e:.1e}"


def fmt_ratio(r):
    if not r:
        return "n/a"
    if r >= 100:
        return f"{r:,.0f}"
    return f"{r:.3g}"


def knob_x(knob, value):
    """The abscissa of a knob value: more work to the right (rtol is plotted as 1/rtol)."""
    v = float(value)
    return 1.0 / v if knob == "rtol" else v


def fit_order(xs, es):
    """Least-squares convergence order over the asymptotic range.

    The asymptotic range is chosen as: the points (in knob order, cheapest first) whose error is
    finite and inside [FIT_LOW, FIT_HIGH] = [1e-12, 1e-2] -- below 1e-2 the step or table spacing
    is already small against the data's scale (pre-asymptotic points are excluded), above 1e-12
    the error is not yet round-off (10^4..10^5 steps accumulate ~1e-13) -- and, of those, the
    first run of consecutive points along which the error keeps decreasing (a plateau or a rise
    ends it). At least 3 points are needed. Fit: log10 e = c - p log10 x, so e ~ x^-p with x = n,
    1/rtol or the table size. Returns (p, x_first, x_last, number of points) or None.
    """
    run = []
    for x, e in zip(xs, es):
        inside = e is not None and FIT_LOW <= e <= FIT_HIGH
        if inside and (not run or e < run[-1][1]):
            run.append((x, e))
        elif run:
            if len(run) >= 3:
                break
            run = [(x, e)] if inside else []
    if len(run) < 3:
        return None
    lx = [math.log10(x) for x, _ in run]
    le = [math.log10(e) for _, e in run]
    mx, me = sum(lx) / len(lx), sum(le) / len(le)
    sxx = sum((a - mx) ** 2 for a in lx)
    sxy = sum((a - mx) * (b - me) for a, b in zip(lx, le))
    slope = sxy / sxx
    return (-slope, run[0][0], run[-1][0], len(run), me - slope * mx)


def case_score(setting, case):
    for c in setting.get("per_case", []):
        if c["case"] == case:
            return c
    return None


def pareto(points):
    """points: (time, error, label). Returns the front: faster-and-no-less-accurate first."""
    front = []
    best = math.inf
    for t, e, label in sorted(points, key=lambda p: (p[0], p[1])):
        if e < best:
            front.append((t, e, label))
            best = e
    return front


FIXED_MARKERS = {"exact": "*", "paper": "P", "eq5": "s", "eq6": "D", "eq7": "v", "eq8": "^",
                 "particle": "X"}


def plot_error_vs_time(data, path):
    fig, axes = plt.subplots(1, 2, figsize=(14, 6.8), sharex=True)
    handles = {}
    for ax, stat in zip(axes, ("max_error", "median_error")):
        for m in data["methods"]:
            name = m["method"]
            colour = COLOURS.get(name, None)
            label = name + (f" (knob {m['knob']})" if m["knob"] else "")
            if any(not s["complete"] for s in m["settings"]):
                label += " *"
            pts = [s for s in m["settings"] if s["seconds_per_ray"] > 0 and s[stat] is not None]
            if not pts:
                continue
            xs = [s["seconds_per_ray"] for s in pts]
            ys = [max(s[stat], ZERO_FLOOR) for s in pts]
            if m["knob"]:
                (h,) = ax.plot(xs, ys, "-", color=colour, lw=1.5)
                ax.annotate(pts[0]["knob_value"], (xs[0], ys[0]), fontsize=7, color=colour,
                            xytext=(-4, 4), textcoords="offset points", ha="right")
                ax.annotate(pts[-1]["knob_value"], (xs[-1], ys[-1]), fontsize=7, color=colour,
                            xytext=(4, -8), textcoords="offset points")
            marker = FIXED_MARKERS.get(name, "o") if not m["knob"] else "o"
            size = 16 if name == "exact" else (8 if not m["knob"] else 4)
            for x, y, s in zip(xs, ys, pts):
                (h,) = ax.plot([x], [y], marker, color=colour, ms=size,
                               mfc=colour if s["complete"] else "none", lw=1.5,
                               ls="-" if m["knob"] else "")
            if name == "exact":
                ax.annotate("exact", (xs[0], ys[0]), fontsize=9, xytext=(9, 2),
                            textcoords="offset points")
            handles[label] = h
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.axhline(ZERO_FLOOR, color="0.6", lw=0.8, ls=":")
        ax.set_xlabel("time per ray, mean over the case set's rays [s]")
        ax.grid(True, which="major", alpha=0.3)
        which = "max" if stat == "max_error" else "median"
        ax.set_ylabel(f"{which} relative error over all rays and channels")
        ax.set_title(f"{which} error vs cost ({data['rays']} rays, "
                     f"{len(data['cases'])} cases)")
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=6,
               fontsize=8, bbox_to_anchor=(0.5, 0.035))
    fig.text(0.01, 0.005,
             "* hollow markers: setting incomplete (failed on some rays, or non-finite there); "
             f"errors of exactly 0 drawn at {ZERO_FLOOR:g} (dotted); non-finite max errors "
             "not drawn. Knob values are written at both ends of each line.",
             fontsize=8)
    fig.tight_layout(rect=(0, 0.11, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def knob_lines(data, m):
    """The lines of one knob panel: (label, xs, errors, style)."""
    xs = [knob_x(m["knob"], s["knob_value"]) for s in m["settings"]]
    lines = [("max over all rays", xs, [s["max_error"] for s in m["settings"]], "-o"),
             ("median over all rays", xs, [s["median_error"] for s in m["settings"]], "--s")]
    if any(c["name"] == SMOOTH_CASE for c in data["cases"]):
        smooth = []
        for s in m["settings"]:
            c = case_score(s, SMOOTH_CASE)
            ok = c is not None and c["failed_rays"] == 0 and c["nonfinite"] == 0
            smooth.append(c["max_error"] if ok else None)
        lines.append((f"max on {SMOOTH_CASE}", xs, smooth, ":^"))
    return lines


def plot_error_vs_knob(data, path):
    knobbed = [m for m in data["methods"] if m["knob"] and m["settings"]]
    fits = {}
    if not knobbed:
        return fits
    cols = 3
    rows = (len(knobbed) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.4 * rows), squeeze=False)
    for ax in axes.flat[len(knobbed):]:
        ax.axis("off")
    for ax, m in zip(axes.flat, knobbed):
        fits[m["method"]] = []
        for (label, xs, es, style), colour in zip(knob_lines(data, m),
                                                  ("tab:red", "tab:blue", "tab:green")):
            pts = [(x, max(e, ZERO_FLOOR)) for x, e in zip(xs, es) if e is not None]
            fit = fit_order(xs, es)
            fits[m["method"]].append((label, fit))
            text = label
            if fit:
                p, x0, x1, k, c = fit
                text += f": order {p:.2f}"
                fx = [x0, x1]
                ax.plot(fx, [10 ** (c - p * math.log10(x)) for x in fx], "-", color=colour,
                        lw=5, alpha=0.25)
            else:
                text += ": no asymptotic range"
            if not pts:
                text = label + ": non-finite at every setting"
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, color=colour, ms=4,
                    label=text)
        ax.set_xscale("log", base=2 if m["knob"] in ("n", "size") else 10)
        ax.set_yscale("log")
        ax.axhspan(FIT_LOW, FIT_HIGH, color="0.9", zorder=0)
        ax.set_xlabel(KNOB_TITLES.get(m["knob"], m["knob"]))
        ax.set_ylabel("relative error")
        title = m["method"] + (" (truncated)" if m["truncated"] else "")
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle("Error against the knob; thick translucent segments are least-squares fits "
                 f"over the asymptotic range (shaded band: errors in [{FIT_LOW:g}, {FIT_HIGH:g}])",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return fits


def target_rows(data, statistic):
    rows = {}
    for t in data["targets"]:
        if t["statistic"] == statistic:
            rows.setdefault(t["method"], {})[t["target"]] = t
    return rows


def setting_by_label(data):
    out = {}
    for m in data["methods"]:
        for s in m["settings"]:
            out[s["label"]] = (m, s)
    return out


def coverage_note(m):
    """Why a method cannot meet any target, if it is incomplete everywhere."""
    if not m["settings"]:
        return "not measured"
    if any(s["complete"] for s in m["settings"]):
        return ""
    s = m["settings"][-1]
    bits = []
    if s["failed_rays"]:
        bits.append(f"fails on {s['failed_rays']} of {s['rays']} rays")
    if s["nonfinite"]:
        bits.append(f"has {s['nonfinite']} non-finite channels")
    return " and ".join(bits) + " at every setting"


def targets_table(data, statistic, targets):
    rows = target_rows(data, statistic)
    by_label = setting_by_label(data)
    exact_med = next((s["median_seconds_per_ray"] for m in data["methods"]
                      if m["method"] == "exact" for s in m["settings"]), 0)
    head = "| method | " + " | ".join(f"{t:.0e}" for t in targets) + " |"
    out = [head, "|---|" + "---|" * len(targets)]
    for m in data["methods"]:
        cells = []
        for t in targets:
            row = rows.get(m["method"], {}).get(t)
            if row and row["reached"]:
                s = by_label[row["label"]][1]
                med = s["median_seconds_per_ray"] / exact_med if exact_med else 0
                setting = row["label"].split(":", 1)[1] if ":" in row["label"] else row["label"]
                cells.append(f"`{setting}`: **{fmt_ratio(row['cost_vs_exact'])}x** "
                             f"({fmt_ratio(med)}x)")
            else:
                why = coverage_note(m)
                if not why and row and row["truncated"]:
                    why = "sweep truncated"
                cells.append("not reached" + (f" ({why})" if why else ""))
        out.append(f"| {m['method']} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def median_ratio(data, label):
    """A setting's median-ray time over exact's median-ray time (0 if unknown)."""
    by_label = setting_by_label(data)
    exact = by_label.get("exact")
    if label not in by_label or not exact or not exact[1]["median_seconds_per_ray"]:
        return 0
    return by_label[label][1]["median_seconds_per_ray"] / exact[1]["median_seconds_per_ray"]


def headline(data, targets):
    """One line per target: the cheapest way of all to reach it, by max and by median error."""
    lines = []
    for t in targets:
        parts = []
        for stat, what in (("max", "on every ray"), ("median", "as a median")):
            reached = [r for r in data["targets"]
                       if r["statistic"] == stat and r["target"] == t and r["reached"]]
            if not reached:
                parts.append(f"{what}: no method reaches it")
                continue
            best = min(reached, key=lambda r: r["cost_vs_exact"] or math.inf)
            cheaper = [r for r in reached if r["method"] != "exact" and r["cost_vs_exact"]
                       and r["cost_vs_exact"] < 1.0]
            text = (f"{what}: cheapest is `{best['label']}` ({fmt_ratio(best['cost_vs_exact'])}x "
                    f"exact)")
            if best["method"] == "exact":
                others = sorted((r for r in reached if r["method"] != "exact"),
                                key=lambda r: r["cost_vs_exact"])
                if others:
                    text += (f"; the next cheapest, `{others[0]['label']}`, costs "
                             f"{fmt_ratio(others[0]['cost_vs_exact'])}x (median ray "
                             f"{fmt_ratio(median_ratio(data, others[0]['label']))}x)")
                else:
                    text += "; no other method reaches it"
            elif cheaper:
                text += ("; cheaper than exact: " +
                         ", ".join(f"`{r['label']}` {fmt_ratio(r['cost_vs_exact'])}x"
                                   for r in sorted(cheaper, key=lambda r: r["cost_vs_exact"])))
            parts.append(text)
        lines.append(f"- **{t:.0e}** -- " + "; ".join(parts) + ".")
    return "\n".join(lines)


def pareto_words(data, stat):
    pts = []
    for m in data["methods"]:
        for s in m["settings"]:
            if s["complete"] and s["seconds_per_ray"] > 0 and s[stat] is not None:
                pts.append((s["seconds_per_ray"], s[stat], s["label"]))
    front = pareto(pts)
    if not front:
        return "no complete setting was measured."
    steps = [f"`{label}` ({fmt_time(t)}, {fmt_err(e)})" for t, e, label in front]
    return " -> ".join(steps)


def sentences(data):
    """The target results in words, one line per method (rows of the two target tables)."""
    rows = target_rows(data, "max")
    med_rows = target_rows(data, "median")
    lines = []
    for m in data["methods"]:
        name = m["method"]
        if name == "exact" or not m["settings"]:
            continue
        last = m["settings"][-1]
        worst = last["worst"]
        where = (f"(case `{worst['case']}`, ray {worst['ray']}, channel "
                 f"{'rgb'[worst['channel']]})")
        note = coverage_note(m)
        if note:
            text = (f"qualifies for no target: it {note}"
                    + (f" (\"{last['failure'][:140]}\")" if last.get("failure") else "")
                    + f". On the rays it ran on, `{last['label']}` has max error "
                    f"{fmt_err(last['max_error'])} {where} and median "
                    f"{fmt_err(last['median_error'])}")
            lines.append(f"- **{name}**: {text}.")
            continue
        parts, never = [], []
        for t in sorted(rows.get(name, {}), reverse=True):
            row, mrow = rows[name][t], med_rows.get(name, {}).get(t)
            if row["reached"]:
                parts.append(f"to reach {t:.0e} on every ray it needs `{row['label']}` and "
                             f"costs {fmt_ratio(row['cost_vs_exact'])}x exact")
            elif mrow and mrow["reached"]:
                parts.append(f"{t:.0e} on every ray is out of reach, but a median error of "
                             f"{t:.0e} takes `{mrow['label']}` at "
                             f"{fmt_ratio(mrow['cost_vs_exact'])}x exact")
            else:
                never.append(f"{t:.0e}")
        if never:
            listed = ", ".join(never[:-1]) + (" and " if len(never) > 1 else "") + never[-1]
            text = listed + (" is" if len(never) == 1 else " are")
            text += " out of reach even as a median"
            loosest = float(never[0])
            incomplete = [s for s in m["settings"] if not s["complete"]
                          and s["median_error"] is not None and s["median_error"] <= loosest]
            if incomplete:
                text += (f" among complete settings (the median of `{incomplete[0]['label']}` is "
                         f"{fmt_err(incomplete[0]['median_error'])}, but it "
                         + ("fails on some rays" if incomplete[0]["failed_rays"] else
                            f"has {incomplete[0]['nonfinite']} non-finite channels") + ")")
            if m["truncated"]:
                text += " (sweep truncated)"
            parts.append(text)
        best_median = min((s["median_error"] for s in m["settings"]
                           if s["median_error"] is not None), default=None)
        tail = (f" Its largest error at `{last['label']}` is {fmt_err(last['max_error'])} {where}"
                f"; its best median error is {fmt_err(best_median)}")
        lines.append(f"- **{name}**: " + "; ".join(parts) + "." + tail + ".")
    return "\n".join(lines)


def orders_table(fits):
    out = ["| method | line | fitted order | fit range (knob) | points |", "|---|---|---|---|---|"]
    for method, rows in fits.items():
        for label, fit in rows:
            if fit:
                p, x0, x1, k, _ = fit
                out.append(f"| {method} | {label} | {p:.2f} | {x0:g} .. {x1:g} | {k} |")
            else:
                out.append(f"| {method} | {label} | -- (no asymptotic range) | | |")
    return "\n".join(out)


def order_notes(fits):
    """Readings of the fitted orders that need the method's definition to make sense."""
    notes = []
    smooth = {m: dict(rows).get(f"max on {SMOOTH_CASE}") for m, rows in fits.items()}
    if smooth.get("ode"):
        notes.append("- `ode`: the knob is the tolerance, so the order is that of error against "
                     "1/rtol; about 1 means the error is proportional to rtol.")
    if smooth.get("rk4") and smooth["rk4"][0] < 3:
        notes.append(f"- `rk4` falls at order {smooth['rk4'][0]:.2f}, not 4, on `{SMOOTH_CASE}`: "
                     "its n steps per segment ignore transfer-function breakpoints inside a "
                     "segment (src/rayint/integrators/rk4.cpp), the segments of that case cross "
                     "its transfer functions' breakpoints, and a kink in rho inside a step "
                     "leaves an O(h^2) error. The median over all rays follows the kink-free rays' order.")
    if smooth.get("riemann"):
        notes.append("- `riemann` samples each step at its midpoint: order 2, kinks included.")
    return ("\n" + "\n".join(notes) + "\n") if notes else ""


def write_readme(data, fits, path, json_name):
    run = data["run"]
    exact = next(m for m in data["methods"] if m["method"] == "exact")["settings"][0]
    targets = sorted({t["target"] for t in data["targets"]}, reverse=True)
    pieces = data.get("pieces", 0)
    per_piece = exact["seconds_per_ray"] * data["rays"] / pieces if pieces else 0

    def load(key):
        la = run.get(key)
        return "unknown" if not la else f"{la['1min']:.2f} / {la['5min']:.2f} / {la['15min']:.2f}"

    failures = []
    for m in data["methods"]:
        if m["truncated"]:
            failures.append(f"- `{m['method']}` was truncated ({m['truncation']}); not measured: "
                            + ", ".join(f"`{s}`" for s in m["skipped"]))
        seen = set()
        for s in m["settings"]:
            if s.get("failure") and s["failure"] not in seen and len(seen) < 1:
                seen.add(s["failure"])
                failures.append(f"- `{m['method']}` failed on {s['failed_rays']} of {s['rays']} "
                                f"rays (first: {s['failure']})")
        nf = [s["label"] for s in m["settings"] if s["nonfinite"]]
        if nf:
            failures.append(f"- `{m['method']}`: non-finite intensities at {len(nf)} of "
                            f"{len(m['settings'])} settings ({nf[0]} .. {nf[-1]})")
    setups = []
    for m in data["methods"]:
        timed = [s for s in m["settings"] if s.get("setup_seconds", 0) >= 0.1]
        if timed:
            setups.append(f"- `{m['method']}`: " + ", ".join(
                f"{s['knob_value'] or s['label']}: {s['setup_seconds']:.3g} s" for s in timed))
    setup_text = ("Constructing the integrators for all cases (tables; not in the time per ray), "
                  "where it took 0.1 s or more:\n\n" + "\n".join(setups)) if setups else ""
    budgets = ", ".join(f"{k} {run[v]:g} s" for k, v in (("--max-seconds", "max_seconds"),
                        ("--method-seconds", "method_max_seconds")) if run[v] > 0) or "none"
    text = f"""# Accuracy and cost of every method (`rayint bench`)

<!-- Generated by reports/make_report.py from {json_name}; do not edit. Regenerate with
     scripts/report.sh -->

Regenerate (build, sweep, plots, this page) with one command:

```sh
./scripts/report.sh
# = build, then: rayint bench --method-seconds 300 -o reports/bench.json   (progress on stderr)
#                /usr/bin/python3 reports/make_report.py reports/bench.json
```

`rayint bench [CASES...] [--methods a,b] [--max-seconds S] [--method-seconds S]` sweeps a subset
(`rayint bench --help`); this run's budgets: {budgets}.

All numbers below come from **one run** of `rayint bench` ([`bench.json`]({json_name})): started
{run['started_at']}, {len(data['cases'])} cases of `cases/` ({data['rays']} rays, {pieces} pieces),
{run['hardware_threads']} hardware threads, load average (1/5/15 min) {load('load_average_start')} at
the start and {load('load_average_end')} at the end (the timings are single-threaded; a load above
~1 means other processes shared the cores and inflated some times). References took
{run['reference_seconds']:.1f} s, measuring every setting {run['measure_seconds']:.0f} s.
{"**The sweep was truncated: " + run['truncation'] + ".**" if run['truncated'] else "The sweep was not truncated."}

![error against time](error_vs_time.png)

[error_vs_time.png](error_vs_time.png): error against time per ray, one line per method along its
knob, the fixed methods as points, `exact` as the star. Left: the largest error over all rays;
right: the median.

![error against knob](error_vs_knob.png)

[error_vs_knob.png](error_vs_knob.png): error against each method's knob with the fitted
convergence order.

## How the numbers are defined

- **Error** of one channel of one ray: `|I - I_ref| / max(|I_ref|, {data['definitions']['underflow_floor']:g})`
  against the 50-digit reference (`src/rayint/reference/`), i.e. the relative error, except where
  the reference is below 1e-290 (at and past double underflow: `thick-absorber-background`, or
  an exact 0), where the absolute error is counted in units of 1e-290 -- the same threshold at
  which `tests/test_exact.cpp` switches from its relative to its absolute criterion. A non-finite
  intensity has infinite error.
- **max error** / **median error** of a setting: over all channels (3 per ray) of all rays of the
  case set that the method ran on.
- **Time per ray**: median over {run['timing']['batches']} batches, each repeating the ray for at least
  {run['timing']['batch_seconds'] * 1e3:g} ms, single thread, without diagnostics and without the
  reference in the loop (references are computed once per ray, up front, and reused for every
  setting). A setting's **time** is the **mean over rays** (= the time to integrate the whole case
  set once / number of rays); the median over rays is also recorded. Table construction
  (`preintegrated`, `psi_table`) happens once per case and is not in the time per ray; it is
  recorded as `setup_seconds`.
- **Cost** = a setting's mean time per ray / `exact`'s mean time per ray, in the same run. In the
  target tables the second figure in parentheses is the same ratio of median-ray times (less
  sensitive to the few very expensive rays -- e.g. the optically thick pieces, where an explicit
  integrator is limited by stability, not accuracy).
- A setting **reaches** a target if it ran on every ray, every channel is finite, and its max
  (or median) error is <= the target; the **cheapest** is the one of least time, with settings
  within {data['definitions']['time_tie_band'] * 100:.0f}% of that time counted as ties and won by the smallest knob.
  These rows are computed by `rayint bench` itself (`cheapest_setting` in
  `src/rayint/studies/sweep.cpp`, tested in `tests/test_sweep.cpp`).

## `exact`

`exact` costs **{fmt_time(exact['seconds_per_ray'])} per ray** (mean; median ray
{fmt_time(exact['median_seconds_per_ray'])}), i.e. **{per_piece * 1e9:.0f} ns per piece** of three
channels over the {pieces} pieces of the case set, {per_piece / 3 * 1e9:.0f} ns per piece and channel
including the ray's splitting at breakpoints and compositing (the issue's target is <= 100 ns per
piece and channel; `bench/bench_exact.cpp` measures the closed form alone, per regime:
`rayint_bench --benchmark_filter=exact --benchmark_repetitions=5`). Its max error is
{fmt_err(exact['max_error'])}, its median {fmt_err(exact['median_error'])}.

## Cheapest setting per target: every ray (max error)

Each cell: the cheapest setting whose **largest** error over all {data['rays']} rays is <= the
target, and its cost as a multiple of `exact` (**mean-time ratio**, (median-ray ratio)).

{targets_table(data, "max", targets)}

## Cheapest setting per target: typical ray (median error)

The same with the **median** error over all channels of all rays <= the target.

{targets_table(data, "median", targets)}

## The Pareto front in words

Cheapest way of all to reach each target (cost = mean-time ratio to `exact`):

{headline(data, targets)}

Method by method (from the rows of the tables above):

{sentences(data)}

Pareto front over all complete settings of all methods, by mean time per ray (every setting not
listed is slower and no more accurate than one that is):

- by **max** error: {pareto_words(data, "max_error")}
- by **median** error: {pareto_words(data, "median_error")}

## Convergence orders

Least-squares slope of log(error) against log(knob) (knob = n, 1/rtol or table size; error ~
knob^-order). The asymptotic range is chosen mechanically: the points whose error lies in
[{FIT_LOW:g}, {FIT_HIGH:g}] -- below 1e-2 the step or table spacing is small against the data
(pre-asymptotic points excluded), above 1e-12 the error is not yet round-off -- and of those the
first run of consecutive points along which the error keeps decreasing (a plateau or a rise ends
it); at least 3 points. The max over all rays is usually set by a few adversarial cases (pulses,
steps, stiff pieces) and need not converge at all; `{SMOOTH_CASE}` is the case made for clean
order studies.

{orders_table(fits)}
{order_notes(fits)}

## Failures, non-finite results, truncation, set-up

{chr(10).join(failures) if failures else "No failures, non-finite results or truncation."}

{setup_text}
"""
    with open(path, "w") as f:
        f.write(text)


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__),
                                                             "bench.json")
    out_dir = os.path.dirname(os.path.abspath(src))
    with open(src) as f:
        data = json.load(f)
    if data.get("report") != "bench":
        sys.exit(f"{src}: not a `rayint bench` report")
    plot_error_vs_time(data, os.path.join(out_dir, "error_vs_time.png"))
    fits = plot_error_vs_knob(data, os.path.join(out_dir, "error_vs_knob.png"))
    write_readme(data, fits, os.path.join(out_dir, "README.md"), os.path.basename(src))
    print(f"wrote {out_dir}/error_vs_time.png, error_vs_knob.png, README.md")


if __name__ == "__main__":
    main()
