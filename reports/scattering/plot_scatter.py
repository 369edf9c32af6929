#!/usr/bin/python3
"""Discrete ordinates (and zonal) error against the Monte Carlo reference, as a function of
bins and grid size, and against cost, from a `rayint scatter` JSON report.

usage: /usr/bin/python3 reports/scattering/plot_scatter.py REPORT.json OUT_PREFIX
writes OUT_PREFIX_error_vs_grid.png and OUT_PREFIX_error_vs_cost.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    report = json.load(open(sys.argv[1]))
    prefix = sys.argv[2]
    noise = report["reference"]["mean_pixel_std_error"]
    runs = report["runs"]
    do = [r for r in runs if r["method"] == "discrete_ordinates"]
    zonal = [r for r in runs if r["method"] == "zonal"]

    fig, ax = plt.subplots(figsize=(6, 4))
    for bins in sorted({r["bins"] for r in do}):
        rs = sorted((r for r in do if r["bins"] == bins), key=lambda r: r["grid"])
        ax.plot([r["grid"] for r in rs], [r["error"]["mean_abs"] for r in rs], "o-", label=f"DO, {bins} bins")
    if zonal:
        rs = sorted(zonal, key=lambda r: r["grid"])
        ax.plot([r["grid"] for r in rs], [r["error"]["mean_abs"] for r in rs], "s--k", label="zonal")
    ax.axhline(noise, color="gray", ls=":", label="MC mean pixel SE")
    ax.set_xlabel("cells per axis")
    ax.set_ylabel("mean |pixel error| vs Monte Carlo")
    ax.set_yscale("log")
    ax.set_title(f"{report['scene'].split('/')[-1]}  ({report['phase']}, albedo {report['albedo']})", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(prefix + "_error_vs_grid.png", dpi=120)

    fig, ax = plt.subplots(figsize=(6, 4))
    for bins in sorted({r["bins"] for r in do}):
        rs = sorted((r for r in do if r["bins"] == bins), key=lambda r: r["grid"])
        ax.plot([r["setup_seconds"] + r["gather_seconds"] for r in rs],
                [r["error"]["mean_abs"] for r in rs], "o-", label=f"DO, {bins} bins")
    if zonal:
        rs = sorted(zonal, key=lambda r: r["grid"])
        ax.plot([r["setup_seconds"] + r["gather_seconds"] for r in rs],
                [r["error"]["mean_abs"] for r in rs], "s--k", label="zonal")
    mc = report["reference"]["every_order"]["seconds"]
    ax.axvline(mc, color="tab:red", ls=":", label=f"MC reference ({report['reference']['spp']} spp)")
    ax.axhline(noise, color="gray", ls=":", label="MC mean pixel SE")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("seconds (setup + gather, 2 cores)")
    ax.set_ylabel("mean |pixel error| vs Monte Carlo")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(prefix + "_error_vs_cost.png", dpi=120)


if __name__ == "__main__":
    main()
