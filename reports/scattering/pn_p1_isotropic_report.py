#!/usr/bin/python3
"""P1 (the diffusion approximation, Marshak's boundary) under diffuse light: the companion of
pn_report.py's P1 map (beam mu0 = 1) with isotropic incident intensity 1 (DISORT's fisot), against
the doubling, over albedo and optical thickness, isotropic and HG 0.75; dotted P3.

Writes reports/scattering/pn_p1_isotropic.json and pn_p1_isotropic.png.

Usage: /usr/bin/python3 reports/scattering/pn_p1_isotropic_report.py [BUILD_DIR]   (default build/)
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from report_env import ROOT, plt, slab  # noqa: E402

OUT = os.path.join(ROOT, "reports", "scattering")
TAUS = [0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100]
ALBEDOS = [0.2, 0.5, 0.8, 0.9, 0.95, 0.99, 1.0]


def rel(a, b):
    return abs(a - b) / abs(b)


def main():
    out = []
    for phase in ("isotropic", "hg:0.75"):
        for a in ALBEDOS:
            for t in TAUS:
                args = ["--tau", repr(t), "--albedo", repr(a), "--phase", phase, "--source", "isotropic",
                        "--mu-up", "1", "--mu-down", "1"]
                d = slab(args, "doubling")["doubling"]
                rec = {"phase": phase, "albedo": a, "tau": t}
                for n in (1, 3):
                    p = slab(args, f"pn:order={n}")["pn"]
                    rec[f"P{n}"] = {"reflectance": rel(p["flux_up_top"], d["flux_up_top"]),
                                    "transmittance": rel(p["diffuse_down_bottom"], d["diffuse_down_bottom"]),
                                    "I_up(1)": rel(p["intensity_up_top"][0], d["intensity_up_top"][0])}
                out.append(rec)
        print("P1 isotropic light map", phase, file=sys.stderr)
    with open(os.path.join(OUT, "pn_p1_isotropic.json"), "w") as f:
        json.dump({"source": "isotropic incident intensity 1", "p1": out}, f, indent=1)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, ax = plt.subplots(2, 2, figsize=(12, 8.5), sharex=True)
    for col, phase in enumerate(("isotropic", "hg:0.75")):
        for row, q in enumerate(("reflectance", "transmittance")):
            a = ax[row][col]
            for i, al in enumerate(ALBEDOS):
                pts = [r for r in out if r["phase"] == phase and r["albedo"] == al]
                a.loglog([r["tau"] for r in pts], [max(r["P1"][q], 1e-17) for r in pts], "o-",
                         color=colors[i % len(colors)], label=f"ω = {al:g}")
                a.loglog([r["tau"] for r in pts], [max(r["P3"][q], 1e-17) for r in pts], ":",
                         color=colors[i % len(colors)])
            a.set_title(f"P1 (diffusion), {phase}, isotropic light: {q}")
            a.set_ylabel("relative error vs doubling")
            a.grid(True, which="both", alpha=0.3)
            if row == 1:
                a.set_xlabel("optical thickness τ")
            a.legend(fontsize=7, ncol=2)
    fig.suptitle("The diffusion approximation (P1, Marshak boundary) under diffuse light; dotted: P3")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "pn_p1_isotropic.png"), dpi=110)


if __name__ == "__main__":
    main()
