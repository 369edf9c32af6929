#!/usr/bin/python3
"""Markdown tables of reports/nerf/README.md from the JSON the CLI wrote:

  eval.json    rayint eval cases --methods ... --format json (corpus: error per method over every
               ray and channel against the 50-digit reference, and the median cost per ray)
  stress.json  rayint stress ... --json (by regime: max / p99 / median relative error)

usage: /usr/bin/python3 reports/nerf/nerf_tables.py reports/nerf/eval.json reports/nerf/stress.json
"""
import json
import statistics
import sys


def corpus_table(path):
    with open(path) as f:
        report = json.load(f)
    per = {}
    for case in report["cases"]:
        for ray in case["rays"]:
            for name, m in ray["methods"].items():
                row = per.setdefault(name, {"rel": [], "seconds": [], "nonfinite": 0, "failed": 0})
                if m.get("failure"):
                    row["failed"] += 1
                    continue
                if not m["finite"]:
                    row["nonfinite"] += 1
                    continue
                row["rel"].extend(x for x in m["rel_error"] if x is not None)
                row["seconds"].append(m["seconds_per_ray"])
    exact_cost = statistics.median(per["exact"]["seconds"]) if per["exact"]["seconds"] else 0
    rays = sum(len(c["rays"]) for c in report["cases"])
    out = [f"{len(report['cases'])} cases, {rays} rays; relative error of the intensity against the "
           "50-digit reference over every ray and channel; cost = median time per ray / exact's "
           f"({exact_cost * 1e6:.2f} µs)", "",
           "| method | max rel | p99 rel | median rel | cost | non-finite / failed rays |",
           "|---|---:|---:|---:|---:|---:|"]
    for name, row in per.items():
        rel = sorted(row["rel"])
        if not rel:
            continue
        p99 = rel[min(len(rel) - 1, int(0.99 * len(rel) + 0.5) - 1)]
        cost = statistics.median(row["seconds"]) / exact_cost if exact_cost else float("nan")
        out.append(f"| `{name}` | {rel[-1]:.2g} | {p99:.2g} | {statistics.median(rel):.2g} | "
                   f"{cost:.2f}× | {row['nonfinite']} / {row['failed']} |")
    return "\n".join(out)


def per_case_table(path, methods):
    with open(path) as f:
        report = json.load(f)
    out = ["| case | rays | " + " | ".join(f"`{m}`" for m in methods) + " |",
           "|---|---:|" + "---:|" * len(methods)]
    for case in report["cases"]:
        cells = []
        for m in methods:
            errs = [x for ray in case["rays"] for x in ray["methods"][m]["rel_error"] if x is not None]
            cells.append(f"{max(errs):.2g}" if errs else "–")
        out.append(f"| {case['name']} | {len(case['rays'])} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def stress_table(path):
    with open(path) as f:
        report = json.load(f)
    methods = report["methods"]
    head = "| regime | samples | " + " | ".join(f"`{m}` max / median" for m in methods) + " |"
    out = [f"seed {report['seed']}, count {report['count']}; relative error of the intensity "
           "(largest of r, g, b) against the 50-digit reference", "", head,
           "|---|---:|" + "---:|" * len(methods)]

    def cell(m):
        r = m["rel_error"]
        fmt = lambda x: "–" if x is None else f"{x:.2g}"
        extra = f" ({m['non_finite']} non-finite)" if m["non_finite"] else ""
        return f"{fmt(r['max'])} / {fmt(r['median'])}{extra}"

    for reg in report["regimes"]:
        by = {m["method"]: m for m in reg["methods"]}
        out.append(f"| {reg['regime']} | {reg['samples']} | " +
                   " | ".join(cell(by[m]) for m in methods) + " |")
    by = {m["method"]: m for m in report["overall"]}
    out.append("| **all** | | " + " | ".join(f"**{cell(by[m])}**" for m in methods) + " |")
    return "\n".join(out)


if __name__ == "__main__":
    print(corpus_table(sys.argv[1]))
    print()
    print("max relative error per case:")
    print()
    print(per_case_table(sys.argv[1], ["exact", "nerf:n=64", "pl_nerf:n=64", "nerf:n=256",
                                       "pl_nerf:n=256", "nerf:at=near:n=64"]))
    print()
    print(stress_table(sys.argv[2]))
