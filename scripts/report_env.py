"""What the report scripts under reports/ start with, once: the repository root, the build
directory (argv[1], default build/), the rayint executable in it, matplotlib without a display,
`rayint slab` runs read as JSON, and the P1 error map both P_N reports draw.

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
    from report_env import BUILD, RAYINT, ROOT, plt, slab  # noqa: E402
"""
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
RAYINT = os.path.join(BUILD, "rayint")


def slab(args, method):
    """`rayint slab --method METHOD --no-integral-equation ARGS`, its JSON report."""
    cmd = [RAYINT, "slab", "--method", method, "--no-integral-equation"] + args
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def p1_map(light, orders, errors, after=None, progress="P1 map"):
    """The runs of the P1 map of reports/scattering/pn_report.py (beam) and pn_p1_isotropic_report.py
    (diffuse light): per phase function (isotropic, hg:0.75), albedo and optical thickness, the slab
    lit by `light` (slab options) through the doubling `d` and P_N of each order `n` in `orders`
    (`p`), both with I_up and I_down at mu = 1. A record {"phase", "albedo", "tau", "P<n>":
    errors(p, d), then after(d)'s entries} per slab."""
    out = []
    for phase in ("isotropic", "hg:0.75"):
        for a in (0.2, 0.5, 0.8, 0.9, 0.95, 0.99, 1.0):
            for t in (0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100):
                args = ["--tau", repr(t), "--albedo", repr(a), "--phase", phase] + light + ["--mu-up", "1", "--mu-down", "1"]
                d = slab(args, "doubling")["doubling"]
                rec = {"phase": phase, "albedo": a, "tau": t}
                for n in orders:
                    rec[f"P{n}"] = errors(slab(args, f"pn:order={n}")["pn"], d)
                if after is not None:
                    rec.update(after(d))
                out.append(rec)
        print(progress, phase, file=sys.stderr)
    return out


def plot_p1_map(records, light, suptitle, path):
    """The P1 map of reports/scattering/pn_report.py (beam) and pn_p1_isotropic_report.py (diffuse
    light): per phase function (isotropic, hg:0.75) and quantity (reflectance, transmittance), the
    relative error of P1 (solid) and P3 (dotted) against the doubling over the optical thickness,
    a line per albedo. `records`: {"phase", "albedo", "tau", "P1": {q: err}, "P3": {q: err}}."""
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, ax = plt.subplots(2, 2, figsize=(12, 8.5), sharex=True)
    albedos = sorted({r["albedo"] for r in records})
    for col, phase in enumerate(("isotropic", "hg:0.75")):
        for row, q in enumerate(("reflectance", "transmittance")):
            a = ax[row][col]
            for i, al in enumerate(albedos):
                pts = [r for r in records if r["phase"] == phase and r["albedo"] == al]
                a.loglog([r["tau"] for r in pts], [max(r["P1"][q], 1e-17) for r in pts], "o-",
                         color=colors[i % len(colors)], label=f"ω = {al:g}")
                a.loglog([r["tau"] for r in pts], [max(r["P3"][q], 1e-17) for r in pts], ":",
                         color=colors[i % len(colors)])
            a.set_title(f"P1 (diffusion), {phase}, {light}: {q}")
            a.set_ylabel("relative error vs doubling")
            a.grid(True, which="both", alpha=0.3)
            if row == 1:
                a.set_xlabel("optical thickness τ")
            a.legend(fontsize=7, ncol=2)
    fig.suptitle(suptitle)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
