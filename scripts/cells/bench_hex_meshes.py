#!/usr/bin/python3
"""Writes the meshes of bench/bench_cell_mesh.cpp (BM_mesh) as files with `rayint bench` cases,
so the issue-29 figure (own interpolation vs VTK's split, hexahedra) is measured by `rayint bench`
on exactly the meshes, field, transfer functions and rays of the Google Benchmark:

  twisted12.vts / twisted12.json   12 x 12 x 12 structured hexahedra on [0, 1]^3, k-layer turned
                                   by 3 degrees per layer (every cell twisted: bilinear faces)
  box12.vts / box12.json           the same grid untwisted (axis-aligned cubes: affine cells)

field s = 0.5 + 0.3 sin(2x) cos(y) + 0.25 z + 0.2 xyz; transfer functions: tests/cell_samples.hpp
breakpoint_tf; 256 parallel rays (16 x 16) tilted by (0.3, 0.2, 1), as bench_rays().

Usage: /usr/bin/python3 scripts/cells/bench_hex_meshes.py OUTDIR
       build/rayint bench OUTDIR/twisted12.json OUTDIR/box12.json -o OUTDIR/bench.json
"""
import json
import math
import os
import sys

import vtk


def grid(n, twist_deg):
    pts = vtk.vtkPoints()
    pts.SetDataTypeToDouble()
    s = vtk.vtkDoubleArray()
    s.SetName("s")
    np_ = n + 1
    for k in range(np_):
        z = k / n
        a = twist_deg * k * math.pi / 180.0
        for j in range(np_):
            for i in range(np_):
                x, y = i / n - 0.5, j / n - 0.5
                p = (0.5 + math.cos(a) * x - math.sin(a) * y, 0.5 + math.sin(a) * x + math.cos(a) * y, z)
                pts.InsertNextPoint(*p)
                s.InsertNextValue(0.5 + 0.3 * math.sin(2 * p[0]) * math.cos(p[1]) + 0.25 * p[2] + 0.2 * p[0] * p[1] * p[2])
    g = vtk.vtkStructuredGrid()
    g.SetDimensions(np_, np_, np_)
    g.SetPoints(pts)
    g.GetPointData().SetScalars(s)
    return g


def rays():
    n = math.sqrt(0.3 ** 2 + 0.2 ** 2 + 1.0)
    d = [0.3 / n, 0.2 / n, 1.0 / n]
    out = []
    for j in range(16):
        for i in range(16):
            out.append({"origin": [0.05 + 0.9 * (i + 0.5) / 16 - 0.15, 0.05 + 0.9 * (j + 0.5) / 16 - 0.1, -0.5],
                        "direction": d})
    return out


TF = {
    "density": {"r": [[0.1, 0.5], [0.3, 4.0], [0.45, 1.0], [0.7, 6.0], [0.9, 2.0]],
                "g": [[0.2, 0.0], [0.5, 3.0], [0.8, 0.5]],
                "b": [[0.0, 1.0], [0.35, 0.2], [0.6, 5.0], [1.0, 1.5]]},
    "color": {"r": [[0.0, 1.0], [0.5, 0.1], [1.0, 0.8]],
              "g": [[0.25, 0.2], [0.55, 1.0], [0.75, 0.0]],
              "b": [[0.4, 0.9], [0.65, 0.3]]},
}


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, twist in (("twisted12", 3.0), ("box12", 0.0)):
        w = vtk.vtkXMLStructuredGridWriter()
        w.SetFileName(os.path.join(out, name + ".vts"))
        w.SetInputData(grid(12, twist))
        w.SetDataModeToBinary()
        w.Write()
        case = {"name": name, "description": "bench/bench_cell_mesh.cpp's BM_mesh mesh (scripts/cells/bench_hex_meshes.py)",
                "transfer_function": TF, "mesh_file": name + ".vts", "rays": rays()}
        with open(os.path.join(out, name + ".json"), "w") as f:
            json.dump(case, f)


if __name__ == "__main__":
    main()
