#!/usr/bin/python3
"""Markdown table of `rayint slab --benchmark ... --json` reports (several may be given; rows in
file order; a later report's row for the same problem and value replaces an earlier one): value,
published, doubling and its deviation, integral equation (isotropic problems) with its error
estimate and deviation, Monte Carlo mean and 95% interval, deviation, z against the published
value, verdict (as computed by rayint slab).

usage: /usr/bin/python3 reports/scattering/disort_table.py REPORT.json [REPORT.json ...]
"""
import json
import sys

rows = {}
for path in sys.argv[1:]:
    for r in json.load(open(path))["rows"]:
        rows[(r["id"], r["value"])] = r

print("| id | value | tol | published | doubling | dev | integral equation (est. err) | dev | "
      "Monte Carlo [95% interval] | dev | z vs published | verdict |")
print("|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---|")
counts = {}
for r in rows.values():
    d, m = r["doubling"], r["monte_carlo"]
    se = m["std_error"]
    z = (m["mean"] - r["published"]) / se if se > 0 else float("nan")
    ie = r.get("integral_equation")
    ie_text = f"{ie['value']:.10g} ({ie['error_estimate']:.0e})" if ie else "-"
    ie_dev = f"{ie['rel_dev']:+.1e}" if ie else "-"
    counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
    print(f"| {r['id']} | {r['value']} | {r['tolerance_rel']:.0e} | {r['published']:.6g} | {d['value']:.8g} | "
          f"{d['rel_dev']:+.1e} | {ie_text} | {ie_dev} | {m['mean']:.7g} [{m['lo95']:.7g}, {m['hi95']:.7g}] | "
          f"{m['rel_dev']:+.1e} | {z:+.1f} | {r['verdict']} |")
print()
print(", ".join(f"{v} {k}" for k, v in sorted(counts.items())))
