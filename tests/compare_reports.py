#!/usr/bin/python3
"""Compare two rayint outputs for equality except their wall-time fields.

usage: compare_reports.py A B

JSON files (reports, stats, shard files) are compared after removing every key whose value is a
wall time or a rate derived from one: keys ending in "seconds", "per_second" or "_share"
(mesh render stats: traversal/integration share of the busy time). Everything else -- counts,
sums, means, standard errors, maxima, medians, p99s, branch histograms, worst cases, pixels --
must be identical, value for value (floats compared as the exact doubles JSON round-trips to).
Any other file (PNG images, text tables) must be byte-identical. Exit 0 if equal, 1 with the
first difference otherwise.
"""
import json
import sys

TIMING_SUFFIXES = ("seconds", "per_second", "_share")


def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not k.endswith(TIMING_SUFFIXES)}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x


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
    a_path, b_path = sys.argv[1], sys.argv[2]
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
