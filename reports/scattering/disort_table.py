#!/usr/bin/python3
"""Markdown table of `rayint slab --benchmark ... --json` reports (several may be given; rows in
file order): value, published, doubling and its deviation, Monte Carlo mean and 95% interval,
deviation, verdict.

usage: /usr/bin/python3 reports/scattering/disort_table.py REPORT.json [REPORT.json ...]
"""
import json
import sys

print("| id | value | tol | published | doubling | dev | Monte Carlo [95% interval] | dev | z vs published | verdict |")
print("|---|---|---:|---:|---:|---:|---|---:|---:|---|")
counts = {}
for path in sys.argv[1:]:
    report = json.load(open(path))
    for r in report["rows"]:
        d, m = r["doubling"], r["monte_carlo"]
        se = m["std_error"]
        z = (m["mean"] - r["published"]) / se if se > 0 else float("nan")
        counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
        print(f"| {r['id']} | {r['value']} | {r['tolerance_rel']:.0e} | {r['published']:.6g} | {d['value']:.7g} | "
              f"{d['rel_dev']:+.1e} | {m['mean']:.7g} [{m['lo95']:.7g}, {m['hi95']:.7g}] | {m['rel_dev']:+.1e} | "
              f"{z:+.1f} | {r['verdict']} |")
print()
print(", ".join(f"{v} {k}" for k, v in sorted(counts.items())))
