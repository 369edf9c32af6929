#!/usr/bin/python3
"""Writes tests/fixtures/cells/vtk_linear_cells.json: VTK's own shape functions, derivatives and
parametric->world map of the linear cells (tetra 10, voxel 11, hexahedron 12, wedge 13,
pyramid 14), evaluated by VTK (vtkCell::EvaluateLocation, InterpolateFunctions,
InterpolateDerivs) at random parametric points of random distorted cells. rayint's
cells/linear_cells.cpp is compared against it in tests/test_linear_cells.cpp ([cells][isoparametric]).

Usage: pvpython scripts/cells/vtk_shape_fixture.py OUT.json   (or /usr/bin/python3 with
Debian's python3-vtk9). Deterministic (seeded). The values come from VTK only.

Cells: the reference nodes of each type (VTK's ParametricCoords) scaled by 2, perturbed by
uniform noise of +-0.3 (15 % of the edge), then rigidly rotated; wedges also mirrored (z -> -z),
which flips the Jacobian sign as gmsh's prism node order does (issue 29). Voxels are
axis-aligned boxes with random edge lengths, as VTK defines them: vtkVoxel::EvaluateLocation
uses only nodes 0, 1, 2 and 4.
"""
import json
import math
import random
import sys

import vtk

TYPES = {
    10: (vtk.vtkTetra, [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]),
    11: (vtk.vtkVoxel, [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]),
    12: (vtk.vtkHexahedron, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]),
    13: (vtk.vtkWedge, [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]),
    14: (vtk.vtkPyramid, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]),
}


def rotation(rng):
    a, b, c = (rng.uniform(0, 2 * math.pi) for _ in range(3))
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    rz = [[ca, -sa, 0], [sa, ca, 0], [0, 0, 1]]
    ry = [[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]]
    rx = [[1, 0, 0], [0, cc, -sc], [0, sc, cc]]
    mul = lambda m, n: [[sum(m[i][k] * n[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return mul(rz, mul(ry, rx))


def random_pcoords(vtk_id, rng):
    while True:
        p = [rng.random() for _ in range(3)]
        if vtk_id == 10 and sum(p) > 1:
            continue
        if vtk_id == 13 and p[0] + p[1] > 1:
            continue
        return p


def main():
    out_path = sys.argv[1]
    rng = random.Random(20261204)
    cells = []
    for vtk_id, (cls, ref) in TYPES.items():
        for k in range(4):
            if vtk_id == 11:
                lo = [rng.uniform(-1, 1) for _ in range(3)]
                size = [rng.uniform(0.5, 2.0) for _ in range(3)]
                nodes = [[lo[i] + size[i] * r[i] for i in range(3)] for r in ref]
            else:
                R = rotation(rng)
                mirror = vtk_id == 13 and k % 2 == 1
                nodes = []
                for r in ref:
                    q = [2 * r[i] + rng.uniform(-0.3, 0.3) for i in range(3)]
                    if mirror:
                        q[2] = -q[2]
                    nodes.append([sum(R[i][j] * q[j] for j in range(3)) for i in range(3)])
            cell = cls()
            n = len(ref)
            for i in range(n):
                cell.GetPointIds().SetId(i, i)
                cell.GetPoints().SetPoint(i, nodes[i])
            samples = []
            for _ in range(15):
                p = random_pcoords(vtk_id, rng)
                sub = vtk.reference(0)
                x = [0.0, 0.0, 0.0]
                w = [0.0] * n
                cell.EvaluateLocation(sub, p, x, w)
                weights = [0.0] * n
                cell.InterpolateFunctions(p, weights)
                derivs = [0.0] * (3 * n)
                cell.InterpolateDerivs(p, derivs)
                samples.append({"pcoords": p, "x": x, "weights": weights, "derivs": derivs})
            cells.append({"vtk_id": vtk_id, "vtk_class": cls.__name__, "nodes": nodes, "samples": samples})
    doc = {
        "generator": "scripts/cells/vtk_shape_fixture.py (do not edit; regenerate with it)",
        "vtk_version": vtk.vtkVersion.GetVTKVersion(),
        "cells": cells,
    }
    with open(out_path, "w") as f:
        json.dump(doc, f, indent=None, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
