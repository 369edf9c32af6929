#!/usr/bin/python3
"""What VTK's tetrahedralisation changes, per cell type, on files gmsh 4.8 and VTK 9.1 wrote
(tests/fixtures/readers/, generate-cells.sh): each file rendered by `rayint render` in the cells'
own interpolation (the default, "mode": "own") and with `--cells split` (vtkDataSetTriangleFilter's
decomposition), same camera (--fit), per-pixel difference max over r, g, b of |split - own|.
The own path itself is checked on a sample of rays: `rayint eval` (own mode) on a small camera of
the same view integrates every chord again with the independent 50-digit cell reference
(reference/cell_reference.hpp) and reports the largest absolute error.

Writes reports/cells/own_vs_split.json and reports/cells/own_vs_split.png; the markdown section
(reports/cells/own_vs_split.md) quotes the JSON.
Run from the repository root:  /usr/bin/python3 scripts/cells/own_vs_split.py [build/rayint]
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build", "rayint")
FIX = os.path.join(ROOT, "tests", "fixtures", "readers")
OUT = os.path.join(ROOT, "reports", "cells")

# (label, file, writer): one file per cell type where the tools wrote one type alone.
FILES = [
    ("voxel (VTK .vtr)", "cells-odd.vtr"),
    ("hexahedron, twisted (VTK .vts)", "cells-twisted.vts"),
    ("hexahedron, twisted block (gmsh)", "cells-hex-41.msh"),
    ("wedge (gmsh prisms)", "cells-prism-41.msh"),
    ("hex + pyramid + tet (gmsh)", "cells-mixed-41.msh"),
    ("all linear types (VTK .vtu)", "cells-all-types.vtu"),
]
# The fixtures' field s spans ~0 .. 1.3; breakpoints inside it (a rough, steep TF like
# reports/cells/accuracy_split.md, so that interpolation differences show).
TF = {"density": [[0.1, 0.5], [0.3, 4.0], [0.45, 1.0], [0.7, 6.0], [0.9, 2.0]],
      "color": [[0.0, 1.0], [0.5, 0.1], [1.0, 0.8]]}
SIZE = 96       # render camera (pixels per side)
SAMPLE = 12     # reference check: a SAMPLE x SAMPLE camera of the same view


def run(args, cwd):
    r = subprocess.run([CLI] + args, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"rayint {' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    return r


def main():
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, name in FILES:
            case = {"name": name, "transfer_function": TF, "mesh_file": os.path.join(FIX, name),
                    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 30,
                               "width": SIZE, "height": SIZE}}
            path = os.path.join(tmp, "case.json")
            json.dump(case, open(path, "w"))
            # A fitted, oblique camera: the case's camera moved by --fit; printed on stderr.
            r = run(["render", path, "--fit", "-o", "own.npy", "--stats", "own.json", "-q"], tmp)
            fitted = json.loads("{" + r.stderr.split("--fit: ", 1)[1].strip() + "}")["camera"]
            case["camera"] = fitted
            json.dump(case, open(path, "w"))
            run(["render", path, "-o", "own.npy", "--stats", "own.json", "-q"], tmp)
            run(["render", path, "--cells", "split", "-o", "split.npy", "-q"], tmp)
            own = np.load(os.path.join(tmp, "own.npy"))[..., :3]
            split = np.load(os.path.join(tmp, "split.npy"))[..., :3]
            stats = json.load(open(os.path.join(tmp, "own.json")))
            diff = np.abs(split - own).max(axis=-1)
            covered = np.abs(own - 0.0).max(axis=-1) > 0  # pixels whose ray met the mesh
            # Pixels whose ray meets one mesh but not the other: the split's planar boundary
            # triangles against the curved (bilinear) boundary faces, at the silhouette.
            one_only = int((covered != (np.abs(split).max(axis=-1) > 0)).sum())
            d = diff[covered]
            # Reference sample: the same view on a SAMPLE x SAMPLE camera, own mode, 50 digits.
            small = dict(case)
            small["camera"] = dict(fitted, width=SAMPLE, height=SAMPLE)
            json.dump(small, open(path, "w"))
            ev = json.loads(run(["eval", path, "-q"], tmp).stdout)["cases"][0]
            errs = [r["abs_error"] for r in ev["rays"] if r["abs_error"] is not None]
            results.append({
                "label": label, "file": name, "cells": stats["mesh"]["cells"]["cells"],
                "pixels": int(covered.sum()), "silhouette_pixels_one_only": one_only, "failed_pixels": stats["failed_pixels"],
                "split_vs_own_median": float(np.median(d)) if d.size else None,
                "split_vs_own_max": float(d.max()) if d.size else None,
                "own_scale": float(own[covered].max()) if d.size else None,
                "reference_rays": len(ev["rays"]), "reference_failed": ev["reference_failed"],
                "reference_rays_hitting": sum(1 for r in ev["rays"] if r["chords"] > 0),
                "reference_chords": sum(r["chords"] for r in ev["rays"]),
                "own_vs_reference_max": max(errs) if errs else None,
            })
            print(results[-1], flush=True)
    os.makedirs(OUT, exist_ok=True)
    json.dump({"tool": "scripts/cells/own_vs_split.py", "size": SIZE, "sample": SAMPLE, "transfer_function": TF,
               "files": results}, open(os.path.join(OUT, "own_vs_split.json"), "w"), indent=2)
    fig, ax = plt.subplots(figsize=(8.5, 4.2))
    x = np.arange(len(results))
    med = [r["split_vs_own_median"] for r in results]
    mx = [r["split_vs_own_max"] for r in results]
    ref = [r["own_vs_reference_max"] or 1e-17 for r in results]
    ax.bar(x - 0.27, med, 0.27, label="split vs own: median per pixel")
    ax.bar(x, mx, 0.27, label="split vs own: max per pixel")
    ax.bar(x + 0.27, ref, 0.27, label=f"own vs 50-digit reference: max ({SAMPLE}x{SAMPLE} rays)")
    ax.set_yscale("log")
    ax.set_xticks(x)
    ax.set_xticklabels([r["label"] for r in results], rotation=20, ha="right", fontsize=8)
    ax.set_ylabel("absolute difference (max over r, g, b)")
    ax.set_title(f"VTK's tetrahedralisation vs the cells' own interpolation ({SIZE}x{SIZE} renders)")
    ax.legend(fontsize=8, loc="center", bbox_to_anchor=(0.5, 0.5))
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "own_vs_split.png"), dpi=110)


if __name__ == "__main__":
    main()
