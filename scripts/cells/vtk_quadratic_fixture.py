#!/usr/bin/python3
"""Writes tests/fixtures/cells/vtk_quadratic_cells.json: VTK's own parametric node coordinates,
shape functions and derivatives of the quadratic cells (quadratic tetra 24, quadratic
hexahedron 25, quadratic wedge 26, triquadratic hexahedron 29, biquadratic-quadratic wedge 32),
evaluated by VTK (vtkCell::GetParametricCoords, InterpolateFunctions, InterpolateDerivs) at
random parametric points inside each cell. VTK 9.1's Python wrapping of
vtkBiQuadraticQuadraticWedge declares InterpolateFunctions/InterpolateDerivs with 15/45 entries
(its header's array sizes; the cell has 18 nodes), so for that cell the weights come from
EvaluateLocation (which takes a weights array of any length) and the derivatives from
vtkCell::Derivatives of the 18 unit nodal fields on the cell placed at its own parametric nodes
(where x = p, so the world derivatives are the parametric ones).
vtkQuadraticPyramid (27): VTK's InterpolateDerivs is not the derivative of its
InterpolateFunctions (VTK 9.1 and 9.2 keep the derivatives of an older set of functions), so its
samples carry "dN" = central differences (h = 1e-5) of VTK's InterpolateFunctions and, for the
record, "dN_vtk" = VTK's InterpolateDerivs.
rayint's cells/quadratic_cells.cpp is compared against it in tests/test_quadratic_cells.cpp
([cells][quadratic]).

Usage: /usr/bin/python3 scripts/cells/vtk_quadratic_fixture.py OUT.json  (Debian's python3-vtk9).
Deterministic (seeded). The values come from VTK only.
"""
import json
import random
import sys

import vtk

CELLS = {24: vtk.vtkQuadraticTetra, 25: vtk.vtkQuadraticHexahedron, 26: vtk.vtkQuadraticWedge,
         29: vtk.vtkTriQuadraticHexahedron, 32: vtk.vtkBiQuadraticQuadraticWedge, 27: vtk.vtkQuadraticPyramid}
WRAPPING_TOO_SHORT = {32}


def inside(vtk_id, p):
    if vtk_id == 24:
        return p[0] + p[1] + p[2] <= 1.0
    if vtk_id in (26, 32):
        return p[0] + p[1] <= 1.0
    return True  # hexahedra; VTK's pyramids: the unit cube with its top face collapsed onto the apex


def main(out):
    rng = random.Random(29)
    result = {"generator": "scripts/cells/vtk_quadratic_fixture.py (VTK %s)" % vtk.vtkVersion.GetVTKVersion(),
              "note": "do not edit: regenerate with the script", "cells": {}}
    for vtk_id, cls in CELLS.items():
        cell = cls()
        n = cell.GetNumberOfPoints()
        pc = cell.GetParametricCoords()
        nodes = [[pc[3 * i + k] for k in range(3)] for i in range(n)]
        samples = []
        while len(samples) < 10:
            p = [rng.random() for _ in range(3)]
            if not inside(vtk_id, p):
                continue
            w = [0.0] * n
            d = [0.0] * (3 * n)
            if vtk_id == 27:
                cell.InterpolateFunctions(p, w)
                d_vtk = [0.0] * (3 * n)
                cell.InterpolateDerivs(p, d_vtk)
                h = 1e-5
                for k in range(3):
                    plus, minus = list(p), list(p)
                    plus[k] += h
                    minus[k] -= h
                    wp, wm = [0.0] * n, [0.0] * n
                    cell.InterpolateFunctions(plus, wp)
                    cell.InterpolateFunctions(minus, wm)
                    for i in range(n):
                        d[k * n + i] = (wp[i] - wm[i]) / (2 * h)
                samples.append({"p": p, "N": w, "dN": d, "dN_vtk": d_vtk})
                continue
            if vtk_id in WRAPPING_TOO_SHORT:
                for i in range(n):
                    cell.GetPointIds().SetId(i, i)
                    cell.GetPoints().SetPoint(i, nodes[i])
                cell.EvaluateLocation(vtk.reference(0), p, [0.0] * 3, w)
                unit = [1.0 if i == j else 0.0 for i in range(n) for j in range(n)]
                cell.Derivatives(0, p, unit, n, d)  # d[3 i + k] = dN_i / dx_k
                d = [d[3 * i + k] for k in range(3) for i in range(n)]  # VTK's InterpolateDerivs layout
            else:
                cell.InterpolateFunctions(p, w)
                cell.InterpolateDerivs(p, d)
            samples.append({"p": p, "N": w, "dN": d})
        result["cells"][str(vtk_id)] = {"name": cls.__name__, "nodes": nodes, "samples": samples}
    json.dump(result, open(out, "w"))


if __name__ == "__main__":
    main(sys.argv[1])
