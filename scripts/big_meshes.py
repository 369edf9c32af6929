#!/usr/bin/python3
"""Writes one tetrahedral mesh in the three binary formats the scaling report loads (issue 33):
the VTK legacy binary .vtk that `rayint generate-mesh` wrote, a .vtu from VTK's own XML writer
(appended raw binary, uncompressed, UInt64 headers) and a gmsh MSH 4.1 binary .msh from meshio.

The points, the tets (in the same order) and the point scalar "s" are the same in all three.

usage: big_meshes.py IN.vtk  (writes IN.vtu and IN.msh beside it)
Needs Debian's python3-vtk9, python3-meshio and numpy (/usr/bin/python3).
"""
import os
import sys
import warnings

import numpy as np


def main():
    if len(sys.argv) != 2 or not sys.argv[1].endswith(".vtk"):
        sys.exit(__doc__)
    src = sys.argv[1]
    stem = src[:-4]
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(src)
    r.ReadAllScalarsOn()
    r.Update()
    grid = r.GetOutput()

    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(stem + ".vtu")
    w.SetInputData(grid)
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()
    w.SetCompressorTypeToNone()
    w.SetHeaderTypeToUInt64()
    if not w.Write():
        sys.exit("vtkXMLUnstructuredGridWriter failed on " + stem + ".vtu")

    import meshio
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float64)
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    s = vtk_to_numpy(grid.GetPointData().GetScalars()).astype(np.float64)
    mesh = meshio.Mesh(points, [("tetra", conn)], point_data={"s": s})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # meshio warns that there are no gmsh:physical tags
        meshio.write(stem + ".msh", mesh, file_format="gmsh", binary=True)
    for ext in (".vtu", ".msh"):
        print("%s%s: %d bytes" % (stem, ext, os.path.getsize(stem + ext)))


if __name__ == "__main__":
    main()
