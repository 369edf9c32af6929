#!/usr/bin/python3
"""Writes tests/fixtures/cells/vtk_quadratic_cells.json: VTK's own parametric node coordinates,
shape functions and derivatives of the quadratic cells (quadratic tetra 24, quadratic
hexahedron 25, quadratic wedge 26), evaluated by VTK (vtkCell::GetParametricCoords,
InterpolateFunctions, InterpolateDerivs) at random parametric points inside each cell.
rayint's cells/quadratic_cells.cpp is compared against it in tests/test_quadratic_cells.cpp
([cells][quadratic]).

Usage: /usr/bin/python3 scripts/cells/vtk_quadratic_fixture.py OUT.json  (Debian's python3-vtk9).
Deterministic (seeded). The values come from VTK only.
"""
import json
import random
import sys

import vtk

CELLS = {24: vtk.vtkQuadraticTetra, 25: vtk.vtkQuadraticHexahedron, 26: vtk.vtkQuadraticWedge}


def inside(vtk_id, p):
    if vtk_id == 24:
        return p[0] + p[1] + p[2] <= 1.0
    if vtk_id == 26:
        return p[0] + p[1] <= 1.0
    return True


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
            cell.InterpolateFunctions(p, w)
            cell.InterpolateDerivs(p, d)
            samples.append({"p": p, "N": w, "dN": d})
        result["cells"][str(vtk_id)] = {"name": cls.__name__, "nodes": nodes, "samples": samples}
    json.dump(result, open(out, "w"))


if __name__ == "__main__":
    main(sys.argv[1])
