#!/usr/bin/python3
"""Records how VTK tetrahedralises each linear cell and writes it as C++ tables:
src/rayint/cells/vtk_split_tables.cpp (do not edit; regenerate with this script) and the check
fixture tests/fixtures/cells/vtk_split_check.json.

Usage: /usr/bin/python3 scripts/cells/vtk_split_tables.py   (from the repository root; VTK 9.1
via Debian's python3-vtk9 or pvpython; ~2 minutes)

Unstructured grids: vtkDataSetTriangleFilter (Filters/General/vtkDataSetTriangleFilter.cxx)
inserts a 3-D cell's points with their parametric coordinates into vtkOrderedTriangulator and
calls TemplateTriangulate, whose result depends only on the order of the cell's global point
ids (it works in parametric space and orders insertion by id), not on the geometry. So for each
type every order pattern of the n ids (n! of them; the lexicographic rank of the pattern is the
table index) is run through the filter once on a single-cell grid, and the tets are recorded as
local node indices (VTK order). The fixture holds random distorted cells with random ids and
VTK's tets for them, which tests/test_linear_cells.cpp compares with the tables (so the
geometry independence is checked, not assumed).
Structured grids (.vts: vtkHexahedron cells, .vtr/.vti: vtkVoxel cells): StructuredExecute
calls cell->TriangulateIds((i + j + k) % 2); both index values are recorded per type.
"""
import itertools
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
    lines = [
        "// VTK's tetrahedralisation of the linear cells, recorded from VTK %s by" % vtk.vtkVersion.GetVTKVersion(),
        "// scripts/cells/vtk_split_tables.py. DO NOT EDIT: regenerate with that script.",
        "// Per type: kXSplits holds the distinct splits (tets as local node indices, VTK order; unused",
        "// rows -1), kXIndex[rank] the split for the order pattern of lexicographic rank `rank`.",
        "#include \"rayint/cells/vtk_split.hpp\"",
        "",
        "namespace rayint::vtk_split_tables {",
        "",
    ]
    for type_id in (12, 11, 13, 14):
        n = len(REF[type_id])
        distinct, index = [], []
        for perm in itertools.permutations(range(n)):
            s = vtk_split(type_id, perm, REF[type_id])
            if s not in distinct:
                distinct.append(s)
            index.append(distinct.index(s))
        name = NAMES[type_id]
        lines.append("const int k%sSplitCount = %d;" % (name, len(distinct)))
        lines.append("const signed char k%sSplits[][kMaxSplitTets][4] = {" % name)
        for s in distinct:
            rows = [list(t) for t in s] + [[-1, -1, -1, -1]] * (6 - len(s))
            lines.append("    {" + ", ".join("{%s}" % ", ".join(map(str, r)) for r in rows) + "},")
        lines.append("};")
        lines.append("const unsigned char k%sIndex[%d] = {" % (name, len(index)))
        for k in range(0, len(index), 40):
            lines.append("    " + ",".join(map(str, index[k:k + 40])) + ",")
        lines.append("};")
        lines.append("")
        print(name, len(distinct), "distinct splits", file=sys.stderr)
    for type_id in (12, 11):
        for idx in (0, 1):
            s = structured_split(type_id, idx)
            lines.append("const signed char k%sStructured%d[5][4] = {%s};" % (
                NAMES[type_id], idx, ", ".join("{%s}" % ", ".join(map(str, t)) for t in s)))
    lines.append("")
    lines.append("}  // namespace rayint::vtk_split_tables")
    with open("src/rayint/cells/vtk_split_tables.cpp", "w") as f:
        f.write("\n".join(lines) + "\n")

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
        json.dump({"generator": "scripts/cells/vtk_split_tables.py (do not edit)",
                   "vtk_version": vtk.vtkVersion.GetVTKVersion(), "cells": checks}, f,
                  separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
