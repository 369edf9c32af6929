#!/usr/bin/python3
"""rayint's quadratic pyramids against VTK's probe and an independent integral (issue 29).

For each file (VTK's blocks of pyramid13, tests/fixtures/quadratic/), 12 random rays: rayint eval
(own mode; its per-ray 50-digit reference error is printed too), VTK's probe along the ray
(scripts/real-files/crosscheck_vtk.py's ray_integral, midpoint rule, 20,000 samples), and for every
ray where the two differ by more than 1e-2 relative an independent integral: VTK's
vtkQuadraticPyramid::InterpolateFunctions, a Newton inverse with central-difference derivatives
over every cell (not VTK's InterpolateDerivs, which are not the functions' derivatives), the
midpoint rule with 6,000 samples (error ~1e-3 from the cuts at the mesh's boundary).

Usage: /usr/bin/python3 scripts/cells/pyramid13_vs_probe.py build/rayint  (python3-vtk9). Seeded.
"""
import json
import os
import random
import subprocess
import sys
import tempfile

import numpy as np
import vtk

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "real-files"))
from crosscheck_vtk import ray_integral  # noqa: E402

FIX = os.path.join(HERE, "..", "..", "tests", "fixtures", "quadratic")
DENSITY, COLOR = [[-1, 0.2], [1.5, 2]], [[-1, 0.1], [1.5, 1]]
TF = {"density": DENSITY, "color": {"r": COLOR, "g": COLOR, "b": COLOR}}


def read(path):
    rd = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkUnstructuredGridReader()
    rd.SetFileName(path)
    rd.Update()
    return rd.GetOutput()


def independent(ds, o, d, t1, n=6000):
    cq = vtk.vtkQuadraticPyramid()
    r = np.array([ds.GetPointData().GetArray("r").GetValue(i) for i in range(ds.GetNumberOfPoints())])
    cells = []
    for c in range(ds.GetNumberOfCells()):
        cell = ds.GetCell(c)
        cells.append((np.array([cell.GetPoints().GetPoint(i) for i in range(13)]), [cell.GetPointId(i) for i in range(13)]))

    def N(p):
        w = [0.0] * 13
        cq.InterpolateFunctions(list(p), w)
        return np.array(w)

    def dN(p, h=1e-7):
        J = np.zeros((13, 3))
        for k in range(3):
            a = np.array(p, float)
            b = a.copy()
            a[k] += h
            b[k] -= h
            J[:, k] = (N(a) - N(b)) / (2 * h)
        return J

    def value(x):
        for X, ids in cells:
            p = np.array([0.5, 0.5, 0.25])
            for _ in range(60):
                try:
                    step = np.linalg.solve(X.T @ dN(p), N(p) @ X - x)
                except np.linalg.LinAlgError:
                    break
                s = np.max(np.abs(step))
                if s > 0.5:
                    step *= 0.5 / s
                p = p - step
                if np.max(np.abs(step)) < 1e-13:
                    if np.all(p >= -1e-9) and np.all(p <= 1 + 1e-9):
                        return float(N(p) @ r[ids])
                    break
        return None

    h = t1 / n
    tau = I = 0.0
    for i in range(n):
        s = value(o + (i + 0.5) * h * d)
        if s is None:
            continue
        rho, col = np.interp(s, *zip(*DENSITY)), np.interp(s, *zip(*COLOR))
        I += col * rho * np.exp(-(tau + rho * h / 2)) * h
        tau += rho * h
    return I


def main(rayint):
    rng = random.Random(13)
    for name in ["block-pyramid13.vtu", "block-pyramid13.vtk"]:
        path = os.path.join(FIX, name)
        ds = read(path)
        b = ds.GetBounds()
        lo, hi = np.array(b[0::2]), np.array(b[1::2])
        diag = float(np.linalg.norm(hi - lo))
        rays = []
        for _ in range(12):
            target = lo + np.array([rng.random() for _ in range(3)]) * (hi - lo)
            d = np.array([rng.uniform(-1, 1) for _ in range(3)])
            d /= np.linalg.norm(d)
            rays.append({"origin": list(target - 1.5 * diag * d), "direction": list(d)})
        with tempfile.TemporaryDirectory() as tmp:
            case = {"name": "p", "transfer_function": {"density": DENSITY, "color": COLOR}, "mesh_file": path,
                    "scalar_field": "r", "rays": rays}
            json.dump(case, open(os.path.join(tmp, "case.json"), "w"))
            subprocess.run([rayint, "eval", "case.json", "--no-timing", "-q", "-o", "out.json"], check=True, cwd=tmp)
            out = json.load(open(os.path.join(tmp, "out.json")))["cases"][0]
        for k, (ray, res) in enumerate(zip(rays, out["rays"])):
            mine = res["intensity"][0]
            probe = ray_integral(ds, "r", ray, TF, 0.0, 3 * diag, 20000)[0]
            line = "%s ray %2d: rayint %.6f (vs 50-digit %.1e)  VTK probe %.6f  rel. diff %.1e" % (
                name, k, mine, res["abs_error"], probe, abs(mine - probe) / max(abs(probe), 1e-300))
            if abs(mine - probe) > 1e-2 * max(abs(probe), 1e-300):
                line += "  independent %.6f" % independent(ds, np.array(ray["origin"]), np.array(ray["direction"]), 3 * diag)
            print(line, flush=True)


if __name__ == "__main__":
    main(os.path.abspath(sys.argv[1]))
