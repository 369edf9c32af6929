#!/usr/bin/python3
"""Gradient error of Riemann renderers vs step count and of psi_table and preintegrated vs table size, from `rayint grad` JSON.

Usage (from the repository root; the commands that made the files in this folder are in
reports/gradients/README.md):
  /usr/bin/python3 reports/gradients/make_table.py reports/gradients/grad.json reports/gradients

Writes table.md (per case, ray and method: max relative gradient error per channel against the
50-digit reference gradient, and the intensity's relative error) and gradient_error_vs_n.png.
"""
import json
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot_errors(ax, pts, label, style, with_intensity):
    """Points (n, gradient error, intensity error), sorted by n: the gradient error in `style`
    and, if asked, the intensity error (floored at 1e-17 for the log scale) dashed in its colour."""
    pts.sort()
    ns = [p[0] for p in pts]
    line, = ax.loglog(ns, [p[1] for p in pts], style, label=f"{label}: gradient")
    if with_intensity:
        ax.loglog(ns, [max(p[2], 1e-17) for p in pts], "s--", color=line.get_color(), alpha=0.6,
                  label=f"{label}: intensity")


def finish_axes(ax, xlabel, title):
    ax.set_xlabel(xlabel)
    ax.set_ylabel("max relative error vs 50-digit reference")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)


def main(path, outdir):
    with open(path) as f:
        report = json.load(f)
    rows = []
    for case in report["cases"]:
        for ray in case["rays"]:
            for label, m in ray["methods"].items():
                if m.get("gradient") is None:
                    rows.append((case["case"], ray["index"], label, None, None))
                    continue
                e = m["errors"]
                g = max(x for x in e["gradient_max_rel_vs_reference"] if x is not None)
                i = max(x for x in e["intensity_rel_vs_reference"] if x is not None)
                rows.append((case["case"], ray["index"], label, g, i))
    lines = ["| case | ray | method | gradient max rel error (worst channel) | intensity rel error (worst channel) |",
             "|---|---|---|---|---|"]
    fmt = lambda x: "failed" if x is None else f"{x:.3g}"
    for c, r, label, g, i in rows:
        lines.append(f"| {c} | {r} | {label} | {fmt(g)} | {fmt(i)} |")
    with open(f"{outdir}/table.md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    fig, (ax, ax_t) = plt.subplots(1, 2, figsize=(12.0, 4.2))
    series = {}
    for c, r, label, g, i in rows:
        mm = re.match(r"riemann:n=(\d+)$", label)
        if not mm or g is None:
            continue
        n = int(mm.group(1))
        series.setdefault((c, r), []).append((n, g, i))
    for (c, r), pts in sorted(series.items()):
        plot_errors(ax, pts, f"{c} ray {r}", "o-", True)
    finish_axes(ax, "Riemann samples per segment n", "What a Riemann renderer's gradient costs in accuracy")

    # psi_table and preintegrated (bilinear lookup): gradient error vs table size.
    tables = {}
    for c, r, label, g, i in rows:
        mm = re.match(r"(psi_table|preintegrated):size=(\d+)$", label)
        if mm and g is not None:
            tables.setdefault((mm.group(1), c, r), []).append((int(mm.group(2)), g, i))
    for (method, c, r), pts in sorted(tables.items()):
        plot_errors(ax_t, pts, f"{method} {c} ray {r}", "o-" if method == "psi_table" else "^-.",
                    method == "psi_table")
    finish_axes(ax_t, "table size (lookup=linear; preintegrated: dims=2, step 2^-6)",
                "... and a table's (derivative of the bilinear table)")
    fig.tight_layout()
    fig.savefig(f"{outdir}/gradient_error_vs_n.png", dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
