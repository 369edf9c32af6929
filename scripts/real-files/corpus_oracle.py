"""Joins the corpus manifests and adds what VTK 9.1 (or meshio, for .msh/.ele) reads from each file.

  /usr/bin/python3 scripts/real-files/corpus_oracle.py OUT      (run by make-corpus.sh)

Reads OUT/manifest-shell.tsv, OUT/manifest-vtk.jsonl, OUT/manifest-paraview.jsonl; writes
OUT/manifest.json: {"tools": {...}, "files": [{file, kind, tool, format, family, field, how,
"oracle": {...} or null, "oracle_error": text}]}. The oracle of a mesh: the reader used, points,
cells by VTK type id, ghost cells (vtkGhostType bit 1), the arrays, and the range of the field (the
manifest's field, else the active scalars); of an image: dimensions, origin, spacing, direction,
arrays, range. count.py compares rayint's reading with it.
"""
import hashlib
import json
import os
import sys

import meshio
import numpy as np
import vtk
from vtk.util import numpy_support as ns

OUT = None  # the corpus folder (main's argument)
MESHIO_VTK = {"vertex": 1, "line": 3, "triangle": 5, "quad": 9, "tetra": 10, "hexahedron": 12, "wedge": 13,
              "pyramid": 14, "line3": 21, "triangle6": 22, "quad8": 23, "tetra10": 24, "hexahedron20": 25,
              "hexahedron27": 29, "quad9": 28, "wedge15": 26, "pyramid13": 27, "wedge18": 32}


def entries():
    files = []
    tsv = os.path.join(OUT, "manifest-shell.tsv")
    if os.path.exists(tsv):
        for line in open(tsv):
            f, kind, tool, fmt, family, field, how = line.rstrip("\n").split("\t")
            files.append({"file": f, "kind": kind, "tool": tool, "format": fmt, "family": family, "field": field or None,
                          "how": how})
    for name in ["manifest-vtk.jsonl", "manifest-paraview.jsonl"]:
        path = os.path.join(OUT, name)
        if os.path.exists(path):
            files += [json.loads(line) for line in open(path)]
    return files


def arrays_of(attrs, assoc):
    out = []
    for k in range(attrs.GetNumberOfArrays()):
        a = attrs.GetAbstractArray(k)
        out.append({"name": a.GetName(), "association": assoc, "components": a.GetNumberOfComponents()})
    return out


def digest(values):
    """sha1 of the values as float64: two files of a family with equal digests hold the same data."""
    return hashlib.sha1(np.ascontiguousarray(np.asarray(values, dtype=np.float64)).tobytes()).hexdigest()[:16]


def linear_residual(points, values):
    """max |value - s(point)| for the corpus's linear field s = 0.5 + 0.3x - 0.2y + 0.4z."""
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    v = np.asarray(values, dtype=float).reshape(-1)
    if len(p) != len(v) or not len(v):
        return None
    return float(np.max(np.abs(v - (0.5 + 0.3 * p[:, 0] - 0.2 * p[:, 1] + 0.4 * p[:, 2]))))


def field_range(ds, field):
    for attrs in [ds.GetPointData(), ds.GetCellData()]:
        a = attrs.GetArray(field) if field else attrs.GetScalars()
        if a is not None and a.GetNumberOfComponents() == 1:
            v = ns.vtk_to_numpy(a).astype(float)
            return [float(v.min()), float(v.max())], a.GetName(), digest(v)
    return None, None, None


def vtk_read(path):
    ext = os.path.splitext(path)[1]
    if ext == ".vtk":
        r = vtk.vtkDataSetReader()
        r.ReadAllScalarsOn()
        r.ReadAllFieldsOn()
    else:
        r = {".vtu": vtk.vtkXMLUnstructuredGridReader, ".pvtu": vtk.vtkXMLPUnstructuredGridReader,
             ".vts": vtk.vtkXMLStructuredGridReader, ".vtr": vtk.vtkXMLRectilinearGridReader,
             ".vti": vtk.vtkXMLImageDataReader, ".pvti": vtk.vtkXMLPImageDataReader}[ext]()
    r.SetFileName(path)
    r.Update()
    ds = r.GetOutput()
    if ds is None or (ds.GetNumberOfPoints() == 0 and ds.GetNumberOfCells() == 0):
        raise RuntimeError("%s read nothing" % r.GetClassName())
    return r.GetClassName(), ds


def mesh_oracle(path, field):
    ext = os.path.splitext(path)[1]
    if ext in (".msh", ".ele"):
        m = meshio.read(path, file_format="tetgen" if ext == ".ele" else "gmsh")
        cells = {}
        for b in m.cells:
            t = MESHIO_VTK.get(b.type, b.type)
            cells[str(t)] = cells.get(str(t), 0) + len(b.data)
        arrays = [{"name": k, "association": "point", "components": 1 if np.ndim(v) == 1 else int(np.shape(v)[1])}
                  for k, v in m.point_data.items()]
        arrays += [{"name": k, "association": "cell", "components": 1} for k in m.cell_data]
        rng = fd = lin = None
        if field and ext == ".ele" and "tetgen:attr1" in m.point_data:
            field = "tetgen:attr1"  # meshio's name of TetGen's first point attribute (TetGen names none)
        if field and field in m.point_data:
            v = np.asarray(m.point_data[field], dtype=float)
            rng, fd = [float(v.min()), float(v.max())], digest(v)
            lin = linear_residual(m.points, v)
        return {"reader": "meshio %s" % meshio.__version__, "points": int(len(m.points)), "cells": cells, "ghost_cells": 0,
                "arrays": arrays, "field": field if rng else None, "range": rng, "field_digest": fd, "linear_residual": lin,
                "points_digest": digest(m.points),
                "bounds": [float(x) for x in np.ravel(list(zip(m.points.min(0), m.points.max(0))))]}
    reader, ds = vtk_read(path)
    cells = {}
    for i in range(ds.GetNumberOfCells()):
        t = str(ds.GetCellType(i))
        cells[t] = cells.get(t, 0) + 1
    ghosts = 0
    g = ds.GetCellData().GetArray("vtkGhostType")
    if g is not None:
        ghosts = int(np.count_nonzero(ns.vtk_to_numpy(g) & 1))
    rng, name, fd = field_range(ds, field)
    pts = ns.vtk_to_numpy(ds.GetPoints().GetData()) if isinstance(ds, vtk.vtkPointSet) and ds.GetPoints() is not None else []
    pa = ds.GetPointData().GetArray(name) if name else None
    lin = linear_residual(pts, ns.vtk_to_numpy(pa)) if pa is not None and len(pts) else None
    return {"reader": reader, "points": ds.GetNumberOfPoints(), "cells": cells, "ghost_cells": ghosts,
            "arrays": arrays_of(ds.GetPointData(), "point") + arrays_of(ds.GetCellData(), "cell"),
            "field": name, "range": rng, "field_digest": fd, "points_digest": digest(pts), "linear_residual": lin, "bounds": list(ds.GetBounds())}


def image_oracle(path, field):
    reader, ds = vtk_read(path)
    rng, name, fd = field_range(ds, field)
    ext = ds.GetExtent()
    direction = [ds.GetDirectionMatrix().GetElement(i, j) for i in range(3) for j in range(3)] \
        if hasattr(ds, "GetDirectionMatrix") else None
    origin = [ds.GetOrigin()[k] + ext[2 * k] * ds.GetSpacing()[k] for k in range(3)]  # corner of the extent (no rotation)
    return {"reader": reader, "dimensions": list(ds.GetDimensions()), "origin": list(ds.GetOrigin()), "extent": list(ext),
            "corner": origin, "spacing": list(ds.GetSpacing()), "direction": direction, "bounds": list(ds.GetBounds()),
            "arrays": arrays_of(ds.GetPointData(), "point") + arrays_of(ds.GetCellData(), "cell"), "field": name,
            "range": rng, "field_digest": fd}


def main():
    global OUT
    OUT = os.path.abspath(sys.argv[1])
    files = entries()
    for e in files:
        path = os.path.join(OUT, e["file"])
        e["oracle"] = None
        try:
            if e["kind"] == "mesh":
                e["oracle"] = mesh_oracle(path, e["field"])
            elif e["kind"] == "image":
                e["oracle"] = image_oracle(path, e["field"])
        except (Exception, SystemExit) as ex:  # the oracle reader cannot read it: recorded, the file stays in the corpus
            e["oracle_error"] = "%s: %s" % (type(ex).__name__, ex)
    tools = {"vtk_oracle": vtk.vtkVersion.GetVTKVersion(), "meshio": meshio.__version__}
    with open(os.path.join(OUT, "manifest.json"), "w") as f:
        json.dump({"tools": tools, "files": files}, f, indent=1)
    kinds = {}
    for e in files:
        kinds[e["kind"]] = kinds.get(e["kind"], 0) + 1
    print("corpus_oracle.py: %s in %s/manifest.json (%d without an oracle reading)" % (
        ", ".join("%d %s" % (n, k) for k, n in sorted(kinds.items())), OUT,
        sum(1 for e in files if e["kind"] != "colormap" and e["oracle"] is None)), file=sys.stderr)


if __name__ == "__main__":
    main()
