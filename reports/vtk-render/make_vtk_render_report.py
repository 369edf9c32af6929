#!/usr/bin/env python3
"""Tables of reports/vtk-render/README.md from results.json (written by scripts/vtk_render.py).
Usage: make_vtk_render_report.py reports/vtk-render > reports/vtk-render/README.md
The prose between the tables is in NOTES.md next to this file (hand-written, with the figures
it quotes taken from these tables); this script prints NOTES.md's head, the tables, its tail."""
import json
import math
import os
import sys

import numpy as np

FLOOR = 2.0 / 255.0


def g(x, digits=3):
    if x is None:
        return "–"
    if isinstance(x, str):
        return x
    if x == 0:
        return "0"
    if abs(x) >= 1e-3 and abs(x) < 1e4:
        return f"{x:.{digits}g}"
    return f"{x:.{digits - 1}e}"


RING = 2  # pixels of the footprint's border left out of "interior"


def region_stats(out, r):
    """Errors by region, from the images the run left next to results.json: interior = hit
    pixels at least RING + 1 pixels inside the mesh's footprint (a (2 RING + 1)^2 neighbourhood of
    hit pixels); edge = the other hit pixels; background = rays that miss the mesh."""
    cdir = os.path.join(out, r["case"])
    exact = np.load(os.path.join(cdir, "exact.npy"))
    got = np.load(os.path.join(out, r["candidate"]))
    with open(os.path.join(out, "cases", r["case"] + ".json")) as f:
        bg = np.array(json.load(f).get("background", [0, 0, 0]), float)
    if got.shape[2] == 4:  # premultiplied RGBA, composited as `rayint check --candidate-alpha premultiplied` does
        got = got[:, :, :3] + (1 - got[:, :, 3:]) * bg
    hit = np.any(np.abs(exact - bg) > 1e-12, axis=2)
    interior = hit.copy()
    for dy in range(-RING, RING + 1):
        for dx in range(-RING, RING + 1):
            interior &= np.roll(np.roll(hit, dy, 0), dx, 1)
    interior[:RING, :] = interior[-RING:, :] = interior[:, :RING] = interior[:, -RING:] = False
    err = np.abs(got - exact).max(axis=2)
    e = np.sort(err[interior])
    edge = hit & ~interior
    return {"n": int(e.size), "max": float(e[-1]), "mean": float(e.mean()),
            "p99": float(e[int(math.ceil(0.99 * e.size)) - 1]), "within": float((e <= FLOOR).mean()),
            "edge_max": float(err[edge].max()) if edge.any() else None,
            "edge_within": float((err[edge] <= FLOOR).mean()) if edge.any() else None,
            "bg_max": float(err[~hit].max()) if (~hit).any() else None}


def length_mismatch(cam):
    """Largest relative difference, over all texels, between the length of a segment measured on
    the ray the Bunyk traversal casts (VTK NDC 2i/W - 1) and on the ray its length computation
    uses (2i/(W-1) - 1), both after the exact camera translation (view angle widened by W/(W-1),
    window centre 1/W): the length of a segment between two depth planes is proportional to the
    norm of the ray direction per unit depth."""
    if "fov_deg" not in cam:
        return 0.0  # orthographic: every ray has the same direction
    w = cam["width"]
    t = math.tan(0.5 * math.radians(cam["fov_deg"])) * w / (w - 1.0)
    c = 1.0 / w
    worst = 0.0
    for i in range(w):
        for j in (0, w // 2, w - 1, i):
            xt, yt = 2.0 * i / w - 1 + c, 2.0 * j / w - 1 + c
            xl, yl = 2.0 * i / (w - 1) - 1 + c, 2.0 * j / (w - 1) - 1 + c
            nt = math.sqrt(1 + (t * xt) ** 2 + (t * yt) ** 2)
            nl = math.sqrt(1 + (t * xl) ** 2 + (t * yl) ** 2)
            worst = max(worst, abs(nl / nt - 1))
    return worst


def main():
    out = sys.argv[1]
    with open(os.path.join(out, "results.json")) as f:
        res = json.load(f)
    with open(os.path.join(out, "NOTES.md")) as f:
        notes = f.read()
    head, _, tail = notes.partition("<!-- tables -->")
    print(head.rstrip() + "\n")
    runs = res["runs"]
    gl = next((r["opengl"] for r in runs if r.get("opengl")), None)
    print(f"VTK {res['vtk_version']} (Debian python3-vtk9)" + (": " + "; ".join(gl) if gl else "") + ".\n")

    print("### Read-back precision\n")
    print("Every value of the candidate file as read back (RGB, and A for the RGBA runs), against the "
          "nearest multiple of 1/255 and of 1/65535:\n")
    print("| case | run | colour buffer bits (R, G, B, A) | max distance of a read-back value from k/255 | from k/65535 |")
    print("|---|---|---|---:|---:|")
    for r in runs:
        if "crashed" in r:
            continue
        v = np.load(os.path.join(out, r["candidate"]))
        q255 = float(np.abs(v * 255 - np.round(v * 255)).max() / 255)
        q65535 = float(np.abs(v * 65535 - np.round(v * 65535)).max() / 65535)
        print(f"| {r['case']} | {r['label']} | {r['color_buffer_bits']} | {g(q255)} | {g(q65535)} |")
    print()

    cases = []
    for r in runs:
        if r["case"] not in cases:
            cases.append(r["case"])
    print("### Error per case, mapper and integrator (from `rayint check`'s JSON)\n")
    print("Tolerance of the check: |got − exact| ≤ max(abs_tol, rel_tol·|exact|) with abs_tol = "
          "2/255 (the 8-bit floor, below) and rel_tol = 0.01; errors are absolute, the largest of the "
          f"three channels. *interior* = pixels whose {2 * RING + 1} × {2 * RING + 1} neighbourhood lies "
          "inside the mesh's footprint (the exact image differs from the background); *edge* = the "
          "other pixels whose ray hits the mesh; *background* = rays that miss it.\n")
    for case in cases:
        rs = [r for r in runs if r["case"] == case]
        print(f"**{case}** ({rs[0]['change']}; figure: [{case}.png]({case}.png))\n")
        print("| run | exit | max rel | mean rel | p99 rel | max abs | PSNR dB | within tol | "
              "interior: max abs | mean abs | p99 abs | within 2/255 | "
              "edge: max abs | within 2/255 | background: max abs | worst pixel |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
        for r in rs:
            if "crashed" in r:
                print(f"| {r['label']} | **VTK crashed ({r['crashed']})** |" + " |" * 13)
                continue
            d = r["rayint"]
            w = d["worst_pixels"][0] if d["worst_pixels"] else None
            wtxt = (f"({w['x']}, {w['y']}) {w['channel']}: {g(w['got'], 4)} vs {g(w['expected'], 4)} "
                    f"[case]({os.path.relpath(w['case_file'], out)})" if w and w.get("case_file") else "–")
            st = region_stats(out, r)
            print(f"| {r['label']} | {r['exit']} | {g(d['rel_error']['max'])} | {g(d['rel_error']['mean'])} | "
                  f"{g(d['rel_error']['p99'])} | {g(d['abs_error']['max'])} | {g(d['psnr_db'])} | "
                  f"{d['fraction_within_tolerance']:.4f} | {g(st['max'])} | {g(st['mean'])} | "
                  f"{g(st['p99'])} | {st['within']:.4f} | {g(st['edge_max'])} | "
                  f"{'–' if st['edge_within'] is None else format(st['edge_within'], '.4f')} | {g(st['bg_max'])} | {wtxt} |")
        print()

    bug = res.get("opacity_control_point_bug")
    if bug:
        print("### VTK's linear integrator's attenuation at the density nodes (one 1e-4 long segment)\n")
        print("| scalar | rayint ρ | VTK, colour nodes at κ's breakpoints only | VTK, colour nodes also at ρ's |")
        print("|---:|---:|---:|---:|")
        for k, s in enumerate(bug["scalar"]):
            print(f"| {s} | {bug['rho'][k]} | {g(bug['vtk_linear_attenuation_literal'][k], 4)} | "
                  f"{g(bug['vtk_linear_attenuation_workaround'][k], 4)} |")
        print()

    cams = {}
    for case in cases:
        with open(os.path.join(out, "cases", case + ".json")) as f:
            cams[case] = json.load(f)["camera"]
    print("### Ray caster: length ray vs traversal ray\n")
    print("The Bunyk traversal finds cells and interpolates scalars on the ray through VTK NDC 2i/W − 1 "
          "but converts depths to lengths on the ray through 2i/(W − 1) − 1. Largest relative length "
          "difference this makes (computed from the cameras, see `make_vtk_render_report.py`):\n")
    for case, cam in cams.items():
        print(f"- {case}: {g(length_mismatch(cam))}")
    print()
    print(tail.strip() + "\n")


if __name__ == "__main__":
    main()
