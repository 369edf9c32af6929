#!/usr/bin/python3
"""Compare two rayint outputs for equality except their wall-time fields.

usage: compare_reports.py A B [--ignore KEY ...]
       compare_reports.py --bench-targets REPORT

JSON files (reports, stats, shard files) are compared after removing every key whose value is a
wall time or a rate derived from one: keys ending in "seconds", "per_second" or "_share"
(mesh render stats: traversal/integration share of the busy time). Everything else -- counts,
sums, means, standard errors, maxima, medians, p99s, branch histograms, worst cases, pixels --
must be identical, value for value (floats compared as the exact doubles JSON round-trips to).
Any other file (PNG images, text tables) must be byte-identical. Exit 0 if equal, 1 with the
first difference otherwise. `--ignore KEY` also removes every key named KEY (a timing field whose
name does not end in one of the suffixes, e.g. the cells study's us_per_ray).

--bench-targets REPORT recomputes the target table of a `rayint bench` report from its settings by
the rule the report states (definitions.target_choice, written here independently of the C++):
for each target, statistic (max, median) and method, the complete settings whose error is <=
the target; the least seconds_per_ray among them; the earliest of those within time_tie_band of
it. Exit 1 if the report's table differs.
"""
import json
import sys

TIMING_SUFFIXES = ("seconds", "per_second", "_share")


IGNORED = set()


def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items()
                if not k.endswith(TIMING_SUFFIXES) and k not in IGNORED}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x


def bench_targets(path):
    r = json.load(open(path))
    band = r["definitions"]["time_tie_band"]
    exact = r["exact_seconds_per_ray"]
    expected = []
    for target in sorted({t["target"] for t in r["targets"]}, reverse=True):
        for stat in ("max", "median"):
            for m in r["methods"]:
                err = lambda s: float("inf") if s[stat + "_error"] is None else s[stat + "_error"]
                ok = [s for s in m["settings"] if s["complete"] and err(s) <= target]
                t = {"target": target, "statistic": stat, "method": m["method"],
                     "reached": bool(ok), "truncated": m["truncated"]}
                if ok:
                    least = min(s["seconds_per_ray"] for s in ok)
                    pick = next(s for s in ok if s["seconds_per_ray"] <= least * (1 + band))
                    t.update(label=pick["label"], error=pick[stat + "_error"],
                             seconds_per_ray=pick["seconds_per_ray"],
                             cost_vs_exact=pick["seconds_per_ray"] / exact if exact > 0 else 0.0)
                expected.append(t)
    d = first_difference(expected, r["targets"], "targets")
    if d:
        print(f"{path}: target table differs from its settings: {d}")
        return 1
    return 0


def first_difference(a, b, path="(root)"):
    if type(a) != type(b):
        return f"{path}: {a!r} != {b!r}"
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{path}.{k}: present in only one"
            d = first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path}: length {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    if a != b and not (a != a and b != b):  # NaN == NaN here
        return f"{path}: {a!r} != {b!r}"
    return None


def main():
    args = sys.argv[1:]
    if args[:1] == ["--bench-targets"]:
        return bench_targets(args[1])
    paths = []
    while args:
        a = args.pop(0)
        if a == "--ignore":
            IGNORED.add(args.pop(0))
        else:
            paths.append(a)
    a_path, b_path = paths
    a_bytes, b_bytes = open(a_path, "rb").read(), open(b_path, "rb").read()
    try:
        a, b = json.loads(a_bytes), json.loads(b_bytes)
    except ValueError:
        if a_bytes != b_bytes:
            print(f"{a_path} and {b_path} differ (bytes)")
            return 1
        return 0
    d = first_difference(strip(a), strip(b))
    if d:
        print(f"{a_path} vs {b_path}: {d}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
