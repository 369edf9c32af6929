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
from report_env import ROOT, p1_map, plot_p1_map  # noqa: E402

OUT = os.path.join(ROOT, "reports", "scattering")


def rel(a, b):
    return abs(a - b) / abs(b)


def main():
    out = p1_map(["--source", "isotropic"], (1, 3),
                 lambda p, d: {"reflectance": rel(p["flux_up_top"], d["flux_up_top"]),
                               "transmittance": rel(p["diffuse_down_bottom"], d["diffuse_down_bottom"]),
                               "I_up(1)": rel(p["intensity_up_top"][0], d["intensity_up_top"][0])},
                 progress="P1 isotropic light map")
    with open(os.path.join(OUT, "pn_p1_isotropic.json"), "w") as f:
        json.dump({"source": "isotropic incident intensity 1", "p1": out}, f, indent=1)
    plot_p1_map(out, "isotropic light",
                "The diffusion approximation (P1, Marshak boundary) under diffuse light; dotted: P3",
                os.path.join(OUT, "pn_p1_isotropic.png"))

if __name__ == "__main__":
    main()
