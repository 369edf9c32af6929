#!/usr/bin/python3
"""Records how VTK tetrahedralises linear cells, as the check fixture
tests/fixtures/cells/vtk_split_check.json: random distorted cells of each type with random global
point ids and the tetrahedra VTK's vtkDataSetTriangleFilter makes of them, which
tests/test_linear_cells.cpp compares with rayint's rule (src/rayint/cells/vtk_split.hpp), so the
rule and its independence of the geometry are checked against VTK, not assumed. (The exhaustive
check over every order of the ids is tests/fixtures/readers/vtk_split_orders.py.)

Usage: /usr/bin/python3 scripts/cells/vtk_split_check.py   (from the repository root; VTK 9.1
via Debian's python3-vtk9 or pvpython)

Unstructured grids: vtkDataSetTriangleFilter (Filters/General/vtkDataSetTriangleFilter.cxx)
inserts a 3-D cell's points with their parametric coordinates into vtkOrderedTriangulator and
calls TemplateTriangulate, whose result depends only on the order of the cell's global point ids.
Structured grids (.vts: vtkHexahedron cells, .vtr/.vti: vtkVoxel cells): StructuredExecute calls
cell->TriangulateIds((i + j + k) % 2).
"""
import json
import random
import sys

import vtk

REF = {
    12: [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
    11: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)],
    13: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)],
    14: [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)],
}
NAMES = {11: "Voxel", 12: "Hexahedron", 13: "Wedge", 14: "Pyramid"}


def vtk_split(type_id, ids, pts):
    """VTK's tets (sorted local node indices) for one cell whose node i has global id ids[i]."""
    n = len(ids)
    ug = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    by_id = [None] * n
    for i in range(n):
        by_id[ids[i]] = pts[i]
    for p in by_id:
        points.InsertNextPoint(p)
    ug.SetPoints(points)
    ug.InsertNextCell(type_id, n, list(ids))
    f = vtk.vtkDataSetTriangleFilter()
    f.SetInputData(ug)
    f.Update()
    out = f.GetOutput()
    tets = []
    for c in range(out.GetNumberOfCells()):
        cell = out.GetCell(c)
        assert cell.GetCellType() == vtk.VTK_TETRA
        tets.append(tuple(sorted(list(ids).index(cell.GetPointId(j)) for j in range(4))))
    return sorted(tets)


def structured_split(type_id, index):
    cell = vtk.vtkHexahedron() if type_id == 12 else vtk.vtkVoxel()
    for i, p in enumerate(REF[type_id]):
        cell.GetPointIds().SetId(i, i)
        cell.GetPoints().SetPoint(i, p)
    ids = vtk.vtkIdList()
    pts = vtk.vtkPoints()
    if hasattr(cell, "TriangulateIds"):
        cell.TriangulateIds(index, ids)
    else:  # VTK 9.1: Triangulate(index, ids, points)
        cell.Triangulate(index, ids, pts)
    local = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
    return [tuple(local[4 * k:4 * k + 4]) for k in range(len(local) // 4)]


def main():
    rng = random.Random(29)
    checks = []
    for type_id in (10, 11, 12, 13, 14):
        for k in range(40):
            ref = REF.get(type_id, [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)])
            n = len(ref)
            ids = list(range(n))
            rng.shuffle(ids)
            if type_id == 11:  # VTK voxels are axis-aligned boxes
                size = [rng.uniform(0.5, 2) for _ in range(3)]
                pts = [[p[i] * size[i] for i in range(3)] for p in ref]
            else:
                pts = [[p[i] + rng.uniform(-0.2, 0.2) for i in range(3)] for p in ref]
            checks.append({"vtk_id": type_id, "ids": ids, "nodes": pts,
                           "tets": [list(t) for t in vtk_split(type_id, ids, pts)]})
    with open("tests/fixtures/cells/vtk_split_check.json", "w") as f:
        json.dump({"generator": "scripts/cells/vtk_split_check.py (do not edit)",
                   "vtk_version": vtk.vtkVersion.GetVTKVersion(), "cells": checks}, f,
                  separators=(",", ":"))
        f.write("\n")
    # The structured-grid tables, printed for comparison with kHexEven/kHexOdd/kVoxelEven/kVoxelOdd
    # in src/rayint/cells/vtk_split.cpp.
    for type_id in (12, 11):
        for index in (0, 1):
            print(NAMES[type_id], index, structured_split(type_id, index))


if __name__ == "__main__":
    main()
