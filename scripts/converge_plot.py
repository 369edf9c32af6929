#!/usr/bin/python3
"""Plot `rayint converge` JSON: per-pixel error (median, p95, max) against the sample distance,
log-log, with the fitted order of each statistic in the legend. Failed steps are marked with x
on the axis, never plotted as a number.

    /usr/bin/python3 scripts/converge_plot.py conv.json -o conv.png [--title TEXT]
"""
import argparse
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("json", nargs="+", help="converge JSON file(s); several give one panel each curve set")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for path in a.json:
        try:
            with open(path) as f:
                r = json.load(f)
            rows = r["rows"]
        except (OSError, ValueError, KeyError) as e:
            print(f"{path}: not a converge JSON ({e})", file=sys.stderr)
            return 2
        label = path if len(a.json) > 1 else ""
        for stat, style in (("median", "o-"), ("p95", "s--"), ("max", "^:")):
            h = [x["step"] for x in rows if not x["failed"] and x[stat] is not None and x[stat] > 0]
            e = [x[stat] for x in rows if not x["failed"] and x[stat] is not None and x[stat] > 0]
            order = r["fits"][stat]["order"]
            tag = f"{stat} (order {order:.2f})" if order is not None else f"{stat} (no fit)"
            ax.loglog(h, e, style, label=f"{label} {tag}".strip())
        failed = [x["step"] for x in rows if x["failed"]]
        if failed:
            ax.plot(failed, [ax.get_ylim()[0]] * len(failed), "rx", label="failed")
    ax.set_xlabel("sample distance")
    ax.set_ylabel("per-pixel error vs exact")
    ax.set_title(a.title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
