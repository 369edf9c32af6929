"""The meshio and VTK 9.1 part of the real-files corpus (run by make-corpus.sh with /usr/bin/python3).

  /usr/bin/python3 scripts/real-files/corpus_vtk.py OUT

Needs OUT/gmsh (make-corpus.sh's gmsh part). Writes OUT/gmsh/*-field.vtk, OUT/meshio/, OUT/vtk/ and
appends one JSON line per file to OUT/manifest-vtk.jsonl: file, kind, tool, format, family, field, how.
Every file is written by meshio's or VTK's own writers; this script only builds the data sets
(VTK sources and filters, or a mesh read back from gmsh's files) and sets the writers' options.
"""
import json
import math
import os
import sys

import meshio
import numpy as np
import vtk

OUT = os.path.abspath(sys.argv[1])
VTK_TOOL = "VTK %s (python3-vtk9)" % vtk.vtkVersion.GetVTKVersion()
MESHIO_TOOL = "meshio %s (python3-meshio)" % meshio.__version__
manifest = open(os.path.join(OUT, "manifest-vtk.jsonl"), "w")


def record(path, kind, tool, fmt, family, field, how):
    manifest.write(json.dumps({"file": os.path.relpath(path, OUT), "kind": kind, "tool": tool, "format": fmt,
                               "family": family, "field": field, "how": how}) + "\n")


def s_of(x, y, z):
    return 0.5 + 0.3 * x - 0.2 * y + 0.4 * z


def clipped_by_plane(clip, data, origin, normal):
    """What the clip filter `clip` (vtkClipDataSet, vtkTableBasedClipDataSet) keeps of `data`
    cut by the plane through `origin` with `normal`."""
    clip.SetInputData(data)
    plane = vtk.vtkPlane()
    plane.SetOrigin(*origin)
    plane.SetNormal(*normal)
    clip.SetClipFunction(plane)
    clip.Update()
    return clip.GetOutput()


# ------------------------------------------------------------------ gmsh's legacy .vtk + the field
# gmsh writes its legacy VTK export without any field; POINT_DATA s is appended here (text), so the
# cells, points and their order stay gmsh's.
for name in sorted(os.listdir(os.path.join(OUT, "gmsh"))):
    if not name.endswith("-mesh.vtk"):
        continue
    src = os.path.join(OUT, "gmsh", name)
    text = open(src).read()
    tokens = text.split("POINTS", 1)[1].split()
    n = int(tokens[0])
    xyz = [float(t) for t in tokens[2:2 + 3 * n]]
    dst = src.replace("-mesh.vtk", "-field.vtk")
    with open(dst, "w") as f:
        f.write(text if text.endswith("\n") else text + "\n")
        f.write("POINT_DATA %d\nSCALARS s double 1\nLOOKUP_TABLE default\n" % n)
        for i in range(n):
            f.write("%.17g\n" % s_of(*xyz[3 * i:3 * i + 3]))
    base = name[:-len("-mesh.vtk")]
    record(dst, "mesh", "gmsh 4.8 .vtk export + POINT_DATA appended by corpus_vtk.py", "vtk legacy ascii (gmsh)",
           "gmsh-" + base, "s", "gmsh Save %s, then POINT_DATA s (double, %%.17g) appended" % name)

# ------------------------------------------------------------------ meshio conversions
os.makedirs(os.path.join(OUT, "meshio"), exist_ok=True)
MESHIO_SOURCES = ["sphere-o1", "box-o1", "twoblocks-o1", "hex-o1", "prism-o1", "mixed-o1", "torus-o2"]
MESHIO_WRITES = [
    ("vtu-ascii.vtu", "vtu ascii", dict(file_format="vtu", binary=False)),
    ("vtu-raw.vtu", "vtu binary (no compression)", dict(file_format="vtu", binary=True, compression=None)),
    ("vtu-zlib.vtu", "vtu binary zlib", dict(file_format="vtu", binary=True, compression="zlib")),
    ("vtu-lzma.vtu", "vtu binary lzma", dict(file_format="vtu", binary=True, compression="lzma")),
    ("vtk42-ascii.vtk", "vtk legacy 4.2 ascii", dict(file_format="vtk", binary=False, fmt_version="4.2")),
    ("vtk51-ascii.vtk", "vtk legacy 5.1 ascii", dict(file_format="vtk", binary=False, fmt_version="5.1")),
    ("vtk51-binary.vtk", "vtk legacy 5.1 binary", dict(file_format="vtk", binary=True, fmt_version="5.1")),
    ("msh22-ascii.msh", "msh 2.2 ascii", dict(file_format="gmsh22", binary=False)),
    ("msh22-binary.msh", "msh 2.2 binary", dict(file_format="gmsh22", binary=True)),
    ("tetgen.ele", "tetgen .node/.ele", dict(file_format="tetgen")),
]
for src in MESHIO_SOURCES:
    m = read_from = None
    for variant in ["41a", "22a"]:  # meshio 5 cannot read some of gmsh's 4.1 files: the 2.2 twin then
        try:
            m, read_from = meshio.read(os.path.join(OUT, "gmsh", "%s-%s.msh" % (src, variant))), variant
            break
        except Exception as e:
            print("corpus_vtk.py: meshio cannot read gmsh/%s-%s.msh: %s" % (src, variant, e), file=sys.stderr)
    if m is None:
        continue
    # meshio 5.0's writers fail on the cell_sets its gmsh reader makes of physical groups (index
    # out of bounds): they are dropped, the cells, point data and gmsh's tags are kept
    tags = {k: v for k, v in m.cell_data.items() if k in ("gmsh:physical", "gmsh:geometrical")}
    if len(tags) < 2:
        tags = {"gmsh:physical": [np.zeros(len(b.data), dtype=int) for b in m.cells],
                "gmsh:geometrical": [np.ones(len(b.data), dtype=int) for b in m.cells]}
    m = meshio.Mesh(m.points, m.cells, point_data=m.point_data, cell_data=tags)
    # the tetgen writer wants a column per attribute and only one cell type: the tetrahedra
    tets = meshio.Mesh(m.points, [b for b in m.cells if b.type == "tetra"],
                       point_data={"s": np.asarray(m.point_data["s"]).reshape(-1, 1)})
    for suffix, fmt, kw in MESHIO_WRITES:
        dst = os.path.join(OUT, "meshio", "%s-%s" % (src, suffix))
        try:
            if kw.get("file_format") == "vtk":  # meshio.write() does not pass fmt_version on
                meshio.vtk.write(dst, m, fmt_version=kw["fmt_version"], binary=kw["binary"])
            elif kw.get("file_format") == "tetgen":
                if not tets.cells:
                    raise ValueError("no tetrahedra")
                meshio.write(dst, tets, **kw)
            else:
                meshio.write(dst, m, **kw)
        except Exception as e:  # a writer that cannot take these cells: noted, not a file
            print("corpus_vtk.py: meshio cannot write %s as %s: %s" % (src, fmt, e), file=sys.stderr)
            continue
        opts = ", ".join("%s=%r" % kv for kv in kw.items())
        record(dst, "mesh", MESHIO_TOOL, fmt, "gmsh-" + src, "s",
               "meshio.read(gmsh/%s-%s.msh), cell_sets dropped%s; meshio.write(%s)" % (
                   src, read_from, ", tetrahedra only, s as a (n, 1) column" if suffix.endswith(".ele") else "", opts))

# ------------------------------------------------------------------ VTK 9.1 writers
V = os.path.join(OUT, "vtk")
os.makedirs(V, exist_ok=True)


def wavelet(extent, spacing=(1, 1, 1)):
    src = vtk.vtkRTAnalyticSource()
    src.SetWholeExtent(*extent)
    src.Update()
    img = vtk.vtkImageData()
    img.DeepCopy(src.GetOutput())
    img.SetSpacing(*spacing)
    return img


def add_point_array(ds, name, fn, vtk_type=vtk.VTK_DOUBLE):
    arr = vtk.vtkDataArray.CreateDataArray(vtk_type)
    arr.SetName(name)
    arr.SetNumberOfTuples(ds.GetNumberOfPoints())
    for i in range(ds.GetNumberOfPoints()):
        arr.SetTuple1(i, fn(*ds.GetPoint(i)))
    ds.GetPointData().AddArray(arr)


def tets_of(ds):
    tri = vtk.vtkDataSetTriangleFilter()
    tri.SetInputData(ds)
    tri.Update()
    out = vtk.vtkUnstructuredGrid()
    out.DeepCopy(tri.GetOutput())
    return out


# the base tetrahedral mesh: VTK's wavelet on 11^3 points, tetrahedralised (5 per voxel), RTData
# (float32, active) plus a double point array and a cell array
base = wavelet((-5, 5, -5, 5, -5, 5), (0.2, 0.2, 0.2))
add_point_array(base, "s", s_of)
base.GetPointData().SetActiveScalars("RTData")
ug = tets_of(base)
cid = vtk.vtkIntArray()
cid.SetName("cell_id")
cid.SetNumberOfTuples(ug.GetNumberOfCells())
for i in range(ug.GetNumberOfCells()):
    cid.SetValue(i, i)
ug.GetCellData().AddArray(cid)
ug.GetPointData().SetActiveScalars("RTData")

COMP = {"none": "SetCompressorTypeToNone", "zlib": "SetCompressorTypeToZLib", "lz4": "SetCompressorTypeToLZ4",
        "lzma": "SetCompressorTypeToLZMA"}


def xml_write(writer, data, path, mode, comp="none", header=32, raw=True, big=False, id32=False, block=None):
    w = writer()
    w.SetInputData(data)
    w.SetFileName(path)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary, "appended": w.SetDataModeToAppended}[mode]()
    getattr(w, COMP[comp])()
    w.SetHeaderTypeToUInt64() if header == 64 else w.SetHeaderTypeToUInt32()
    w.SetEncodeAppendedData(0 if raw else 1)
    if big:
        w.SetByteOrderToBigEndian()
    if id32:
        w.SetIdTypeToInt32()
    if block:
        w.SetBlockSize(block)
    assert w.Write() == 1, path
    opts = "mode=%s compressor=%s header=UInt%d%s%s%s%s" % (
        mode, comp, header, "" if mode != "appended" else (" raw" if raw else " base64"), " big-endian" if big else "",
        " Int32 ids" if id32 else "", " block=%d" % block if block else "")
    return opts


def ug_xml(name, **kw):
    path = os.path.join(V, name)
    opts = xml_write(vtk.vtkXMLUnstructuredGridWriter, ug, path, **kw)
    record(path, "mesh", VTK_TOOL, "vtu " + opts, "vtk-wavelet-tets", "RTData",
           "vtkRTAnalyticSource 11^3 spacing 0.2 -> vtkDataSetTriangleFilter; vtkXMLUnstructuredGridWriter " + opts)


ug_xml("tets-ascii.vtu", mode="ascii")
for comp in ["none", "zlib", "lz4", "lzma"]:
    for header in [32, 64]:
        ug_xml("tets-binary-%s-h%d.vtu" % (comp, header), mode="binary", comp=comp, header=header)
        ug_xml("tets-appraw-%s-h%d.vtu" % (comp, header), mode="appended", comp=comp, header=header)
ug_xml("tets-appb64-none.vtu", mode="appended", raw=False)
ug_xml("tets-appb64-zlib.vtu", mode="appended", comp="zlib", raw=False)
ug_xml("tets-appraw-zlib-bigendian.vtu", mode="appended", comp="zlib", big=True)
ug_xml("tets-appraw-lz4-int32ids-block4096.vtu", mode="appended", comp="lz4", id32=True, block=4096)


def legacy_write(data, path, binary, version=None):
    w = vtk.vtkUnstructuredGridWriter() if isinstance(data, vtk.vtkUnstructuredGrid) else vtk.vtkDataSetWriter()
    w.SetInputData(data)
    w.SetFileName(path)
    w.SetFileTypeToBinary() if binary else w.SetFileTypeToASCII()
    if version:
        w.SetFileVersion(version)
    assert w.Write() == 1, path
    return "%s%s" % ("binary" if binary else "ascii", " FileVersion %d" % version if version else "")


def with_points(data, vtk_type):
    out = vtk.vtkUnstructuredGrid()
    out.DeepCopy(data)
    pts = vtk.vtkPoints()
    pts.SetDataType(vtk_type)
    pts.SetNumberOfPoints(data.GetNumberOfPoints())
    for i in range(data.GetNumberOfPoints()):
        pts.SetPoint(i, data.GetPoint(i))
    out.SetPoints(pts)
    return out


for ptype, tname in [(vtk.VTK_FLOAT, "float"), (vtk.VTK_DOUBLE, "double")]:
    data = with_points(ug, ptype)
    for binary in [False, True]:
        for version in [None, 42]:
            name = "tets-legacy-%s-%s%s.vtk" % ("binary" if binary else "ascii", tname, "-v42" if version else "")
            opts = legacy_write(data, os.path.join(V, name), binary, version)
            record(os.path.join(V, name), "mesh", VTK_TOOL, "vtk legacy %s %s points" % (opts, tname),
                   "vtk-wavelet-tets", "RTData", "the same tets, points as %s; vtkUnstructuredGridWriter %s" % (tname, opts))

# parallel files: vtkXMLPUnstructuredGridWriter, pieces from vtkExtractUnstructuredGridPiece, with
# and without one level of ghost cells
for pieces, ghost in [(2, 1), (3, 1), (3, 0)]:
    split = vtk.vtkExtractUnstructuredGridPiece()
    split.SetInputData(ug)
    split.SetCreateGhostCells(1 if ghost else 0)
    name = "tets-p%d-g%d.pvtu" % (pieces, ghost)
    pw = vtk.vtkXMLPUnstructuredGridWriter()
    pw.SetInputConnection(split.GetOutputPort())
    pw.SetFileName(os.path.join(V, name))
    pw.SetNumberOfPieces(pieces)
    pw.SetStartPiece(0)
    pw.SetEndPiece(pieces - 1)
    pw.SetGhostLevel(ghost)
    pw.SetDataModeToAppended()
    pw.SetCompressorTypeToZLib()
    assert pw.Write() == 1
    record(os.path.join(V, name), "mesh", VTK_TOOL, "pvtu %d pieces ghost level %d" % (pieces, ghost),
           "vtk-wavelet-tets", "RTData", "vtkExtractUnstructuredGridPiece(CreateGhostCells=%d) -> "
           "vtkXMLPUnstructuredGridWriter pieces=%d ghost level %d appended zlib" % (ghost, pieces, ghost))

# cell data only: the tets with the cell array c = s at the cell centre, no point array
cd = vtk.vtkUnstructuredGrid()
cd.DeepCopy(ug)
for k in range(cd.GetPointData().GetNumberOfArrays() - 1, -1, -1):
    cd.GetPointData().RemoveArray(k)
cc = vtk.vtkDoubleArray()
cc.SetName("c")
cc.SetNumberOfTuples(cd.GetNumberOfCells())
for i in range(cd.GetNumberOfCells()):
    b = cd.GetCell(i).GetBounds()
    cc.SetValue(i, s_of((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2))
cd.GetCellData().RemoveArray("cell_id")
cd.GetCellData().AddArray(cc)
p = os.path.join(V, "tets-celldata.vtu")
xml_write(vtk.vtkXMLUnstructuredGridWriter, cd, p, "appended", "zlib")
record(p, "mesh", VTK_TOOL, "vtu appended zlib, cell data only", "vtk-celldata", "c",
       "the tets with only a cell array c (s at the bounding-box centre); vtkXMLUnstructuredGridWriter")
p = os.path.join(V, "tets-celldata.vtk")
legacy_write(cd, p, True)
record(p, "mesh", VTK_TOOL, "vtk legacy binary, cell data only", "vtk-celldata", "c", "as tets-celldata.vtu, vtkUnstructuredGridWriter binary")

# quadratic tetrahedra: every tet of a coarse wavelet mesh with its edge midpoints (VTK type 24), s exact
small = tets_of(wavelet((0, 3, 0, 3, 0, 3), (0.5, 0.5, 0.5)))
q = vtk.vtkUnstructuredGrid()
qp = vtk.vtkPoints()
qp.SetDataTypeToDouble()
for i in range(small.GetNumberOfPoints()):
    qp.InsertNextPoint(small.GetPoint(i))
mid = {}
q.Allocate(small.GetNumberOfCells())
for c in range(small.GetNumberOfCells()):
    ids = [small.GetCell(c).GetPointId(k) for k in range(4)]
    nodes = list(ids)
    for a, b in [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]:  # vtkQuadraticTetra's edge order
        key = tuple(sorted((ids[a], ids[b])))
        if key not in mid:
            pa, pb = small.GetPoint(ids[a]), small.GetPoint(ids[b])
            mid[key] = qp.InsertNextPoint([(pa[k] + pb[k]) / 2 for k in range(3)])
        nodes.append(mid[key])
    q.InsertNextCell(vtk.VTK_QUADRATIC_TETRA, 10, nodes)
q.SetPoints(qp)
add_point_array(q, "s", s_of)
for name, fn in [("tet10.vtu", lambda d, pth: xml_write(vtk.vtkXMLUnstructuredGridWriter, d, pth, "appended", "zlib")),
                 ("tet10.vtk", lambda d, pth: legacy_write(d, pth, False))]:
    fn(q, os.path.join(V, name))
    record(os.path.join(V, name), "mesh", VTK_TOOL, name.split(".")[1] + " quadratic tetra (VTK 24)", "vtk-tet10", "s",
           "vtkDataSetTriangleFilter of a 4^3 wavelet, edge midpoints added (vtkQuadraticTetra order), s exact at all nodes")

# other cell types: voxels (vtkAppendFilter of an image), a clipped image (vtkTableBasedClipDataSet:
# hexahedra, wedges, pyramids, tetrahedra), structured grids
vox_src = wavelet((-3, 3, -3, 3, -3, 3), (0.3, 0.3, 0.3))
add_point_array(vox_src, "s", s_of)
vox_src.GetPointData().SetActiveScalars("s")
app = vtk.vtkAppendFilter()
app.SetInputData(vox_src)
app.Update()
for name, fn, fmt in [("voxels.vtu", lambda d, pth: xml_write(vtk.vtkXMLUnstructuredGridWriter, d, pth, "binary", "zlib"), "vtu"),
                      ("voxels.vtk", lambda d, pth: legacy_write(d, pth, True), "vtk legacy binary")]:
    fn(app.GetOutput(), os.path.join(V, name))
    record(os.path.join(V, name), "mesh", VTK_TOOL, fmt + " voxels (VTK 11)", "vtk-voxels", "s",
           "vtkRTAnalyticSource 7^3 spacing 0.3 -> vtkAppendFilter (image to unstructured grid: voxels)")
p = os.path.join(V, "clip-mixed.vtu")
xml_write(vtk.vtkXMLUnstructuredGridWriter, clipped_by_plane(vtk.vtkTableBasedClipDataSet(), vox_src, (0.1, 0.05, 0), (1, 0.4, 0.2)),
          p, "appended", "zlib")
record(p, "mesh", VTK_TOOL, "vtu mixed linear cells", "vtk-clip", "s",
       "the 7^3 wavelet image clipped by a plane: vtkTableBasedClipDataSet (voxels, wedges, pyramids, tets)")
i2p = vtk.vtkImageDataToPointSet()
i2p.SetInputData(vox_src)
i2p.Update()
sg = vtk.vtkStructuredGrid()
sg.DeepCopy(i2p.GetOutput())
pts = sg.GetPoints()
for i in range(sg.GetNumberOfPoints()):  # a gentle bend: hexahedra that are not voxels
    x, y, z = pts.GetPoint(i)
    pts.SetPoint(i, x, y + 0.1 * x * x, z + 0.05 * y)
for name, mode, comp in [("bent-ascii.vts", "ascii", "none"), ("bent-appended-lz4.vts", "appended", "lz4")]:
    xml_write(vtk.vtkXMLStructuredGridWriter, sg, os.path.join(V, name), mode, comp)
    record(os.path.join(V, name), "mesh", VTK_TOOL, "vts %s %s" % (mode, comp), "vtk-bent-vts", "s",
           "7^3 wavelet -> vtkImageDataToPointSet, points bent (y += 0.1x^2, z += 0.05y); vtkXMLStructuredGridWriter")
rg = vtk.vtkRectilinearGrid()
xs, ys, zs = [-1, -0.7, -0.2, 0, 0.5, 1.2], [-1, 0, 0.3, 1], [-0.5, 0, 0.25, 0.5, 1]
rg.SetDimensions(len(xs), len(ys), len(zs))
for setter, vals in [(rg.SetXCoordinates, xs), (rg.SetYCoordinates, ys), (rg.SetZCoordinates, zs)]:
    arr = vtk.vtkDoubleArray()
    for v in vals:
        arr.InsertNextValue(v)
    setter(arr)
add_point_array(rg, "s", s_of)
for name, mode, comp in [("rect-binary.vtr", "binary", "zlib"), ("rect-appended-lzma.vtr", "appended", "lzma")]:
    xml_write(vtk.vtkXMLRectilinearGridWriter, rg, os.path.join(V, name), mode, comp)
    record(os.path.join(V, name), "mesh", VTK_TOOL, "vtr %s %s" % (mode, comp), "vtk-rect", "s",
           "vtkRectilinearGrid 6x4x5 uneven coordinates, s; vtkXMLRectilinearGridWriter")

# overlapping meshes: two tetrahedralised wavelets, the second moved by half its size, appended
# without merging points (what Append Datasets gives) -> rayint must refuse
moved = vtk.vtkTransformFilter()
tf = vtk.vtkTransform()
tf.Translate(0.5, 0.3, 0.2)
moved.SetTransform(tf)
moved.SetInputData(small)
app2 = vtk.vtkAppendFilter()
app2.AddInputData(small)
app2.AddInputConnection(moved.GetOutputPort())
app2.Update()
p = os.path.join(V, "overlap-appended.vtu")
xml_write(vtk.vtkXMLUnstructuredGridWriter, app2.GetOutput(), p, "appended", "zlib")
record(p, "mesh", VTK_TOOL, "vtu two overlapping meshes", "vtk-overlap", "RTData",
       "vtkAppendFilter of a tetrahedralised 4^3 wavelet and its copy moved by (0.5, 0.3, 0.2): overlapping (must be refused)")

# more of what VTK writes: several <Piece>s in one .vtu, a legacy file with two SCALARS and FIELD
# data, an empty output (a clip that removed everything), polyhedra, Lagrange tetrahedra
# SetNumberOfPieces on the writer of a data set given directly: the pipeline cannot split it, so
# every <Piece> holds the whole mesh (VTK's reader reads it three times over): must be refused
w = vtk.vtkXMLUnstructuredGridWriter()
w.SetInputData(ug)
w.SetFileName(os.path.join(V, "tets-3pieces-whole.vtu"))
w.SetNumberOfPieces(3)
assert w.Write() == 1
record(os.path.join(V, "tets-3pieces-whole.vtu"), "mesh", VTK_TOOL, "vtu 3 <Piece>s, each the whole mesh", "vtk-triplicate",
       "RTData", "vtkXMLUnstructuredGridWriter SetInputData(tets) + SetNumberOfPieces(3): each Piece is the whole mesh (must be refused)")
# through vtkExtractUnstructuredGridPiece, which answers piece requests: 3 distinct Pieces in one file
split3 = vtk.vtkExtractUnstructuredGridPiece()
split3.SetInputData(ug)
w = vtk.vtkXMLUnstructuredGridWriter()
w.SetInputConnection(split3.GetOutputPort())
w.SetFileName(os.path.join(V, "tets-3pieces.vtu"))
w.SetNumberOfPieces(3)
assert w.Write() == 1
record(os.path.join(V, "tets-3pieces.vtu"), "mesh", VTK_TOOL, "vtu 3 <Piece>s in one file", "vtk-wavelet-tets", "RTData",
       "vtkExtractUnstructuredGridPiece -> vtkXMLUnstructuredGridWriter SetNumberOfPieces(3) (one file, 3 Pieces)")
fd = vtk.vtkUnstructuredGrid()
fd.DeepCopy(ug)
fld = vtk.vtkDoubleArray()
fld.SetName("TimeValue")
fld.InsertNextValue(1.5)
fd.GetFieldData().AddArray(fld)
fd.GetPointData().SetActiveScalars("RTData")
p = os.path.join(V, "tets-fielddata.vtk")
legacy_write(fd, p, False)
record(p, "mesh", VTK_TOOL, "vtk legacy ascii, two point SCALARS, a cell array, FIELD data", "vtk-wavelet-tets-fielddata", "RTData",
       "the wavelet tets with a FIELD TimeValue; vtkUnstructuredGridWriter ascii")


def write_vtu_and_vtk(data, stem, what, family, field, how):
    """`data` as V/<stem>.vtu (XML appended, zlib) and V/<stem>.vtk (legacy ASCII), each recorded
    with the format "vtu <what>" / "vtk <what>"."""
    for ext, write in [("vtu", lambda pth: xml_write(vtk.vtkXMLUnstructuredGridWriter, data, pth, "appended", "zlib")),
                       ("vtk", lambda pth: legacy_write(data, pth, False))]:
        path = os.path.join(V, stem + "." + ext)
        write(path)
        record(path, "mesh", VTK_TOOL, ext + " " + what, family, field, how)


write_vtu_and_vtk(clipped_by_plane(vtk.vtkClipDataSet(), ug, (100, 0, 0), (1, 0, 0)), "empty", "empty (0 cells)",
                  "vtk-empty", "RTData",
                  "vtkClipDataSet of the wavelet tets by a plane beyond it: an empty output, written as it is")
# one polyhedron (a cube given by its 6 faces) and its neighbour tetrahedron
poly_ug = vtk.vtkUnstructuredGrid()
pp = vtk.vtkPoints()
for xyz in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (2, 0.5, 0.5)]:
    pp.InsertNextPoint(xyz)
poly_ug.SetPoints(pp)
faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
fl = vtk.vtkIdList()
fl.InsertNextId(len(faces))
for f in faces:
    fl.InsertNextId(len(f))
    for i in f:
        fl.InsertNextId(i)
poly_ug.InsertNextCell(vtk.VTK_POLYHEDRON, fl)  # the face stream: nfaces, (n, ids...) per face
poly_ug.InsertNextCell(vtk.VTK_TETRA, 4, [1, 2, 5, 8])
add_point_array(poly_ug, "s", s_of)
write_vtu_and_vtk(poly_ug, "polyhedron", "polyhedron (VTK 42) + tetra", "vtk-polyhedron", "s",
                  "a cube as one vtkPolyhedron (6 faces) and a tetrahedron beside it")
lag = vtk.vtkUnstructuredGrid()
lp = vtk.vtkPoints()
for xyz in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (0.5, 0, 0), (0.5, 0.5, 0), (0, 0.5, 0), (0, 0, 0.5), (0.5, 0, 0.5), (0, 0.5, 0.5)]:
    lp.InsertNextPoint(xyz)
lag.SetPoints(lp)
lag.InsertNextCell(vtk.VTK_LAGRANGE_TETRAHEDRON, 10, list(range(10)))
add_point_array(lag, "s", s_of)
p = os.path.join(V, "lagrange-tet.vtu")
xml_write(vtk.vtkXMLUnstructuredGridWriter, lag, p, "appended", "zlib")
record(p, "mesh", VTK_TOOL, "vtu Lagrange tetrahedron (VTK 71), order 2", "vtk-lagrange", "s",
       "one vtkLagrangeTetra of order 2 (10 nodes), s exact at its nodes")

# ------------------------------------------------------------------ images
img = wavelet((-4, 4, -2, 4, 1, 5), (0.25, 0.3, 0.5))
img.SetOrigin(0.5, -1, 2)
add_point_array(img, "s", s_of)
img.GetPointData().SetActiveScalars("RTData")
cell = vtk.vtkDoubleArray()
cell.SetName("cell_s")
cell.SetNumberOfTuples(img.GetNumberOfCells())
for i in range(img.GetNumberOfCells()):
    cell.SetValue(i, 0.5 + 0.001 * i)
img.GetCellData().AddArray(cell)


def img_xml(name, data, family, note, **kw):
    path = os.path.join(V, name)
    opts = xml_write(vtk.vtkXMLImageDataWriter, data, path, **kw)
    record(path, "image", VTK_TOOL, "vti " + opts + note, family, {"vtk-wavelet-image": "RTData", "vtk-wavelet-s": "s"}.get(family),
           "vtkRTAnalyticSource extent (-4,4,-2,4,1,5) spacing (0.25,0.3,0.5) origin (0.5,-1,2), + point s, cell cell_s; "
           "vtkXMLImageDataWriter " + opts + note)


img_xml("wavelet-ascii.vti", img, "vtk-wavelet-image", "", mode="ascii")
img_xml("wavelet-binary.vti", img, "vtk-wavelet-image", "", mode="binary")
img_xml("wavelet-appraw-zlib.vti", img, "vtk-wavelet-image", "", mode="appended", comp="zlib")
img_xml("wavelet-appraw-lz4.vti", img, "vtk-wavelet-image", "", mode="appended", comp="lz4")
img_xml("wavelet-appraw-lzma-h64.vti", img, "vtk-wavelet-image", "", mode="appended", comp="lzma", header=64)
img_xml("wavelet-appb64-zlib.vti", img, "vtk-wavelet-image", "", mode="appended", comp="zlib", raw=False)
rot = vtk.vtkImageData()
rot.DeepCopy(img)
c, s = math.cos(0.3), math.sin(0.3)
rot.SetDirectionMatrix(c, -s, 0, s, c, 0, 0, 0, 1)
img_xml("wavelet-rotated.vti", rot, "vtk-wavelet-rotated", " Direction rotated 0.3 rad about z", mode="appended", comp="zlib")
conly = vtk.vtkImageData()
conly.DeepCopy(img)
for k in range(conly.GetPointData().GetNumberOfArrays() - 1, -1, -1):
    conly.GetPointData().RemoveArray(k)
img_xml("wavelet-celldata.vti", conly, "vtk-wavelet-celldata", " cell data only", mode="appended", comp="zlib")
# images as scanners and simulations store them: unsigned 8-bit and signed 16-bit values, the
# active array not the first one, big-endian
for name, vtk_type, tname in [("ct-uint8.vti", vtk.VTK_UNSIGNED_CHAR, "UInt8"), ("ct-int16.vti", vtk.VTK_SHORT, "Int16")]:
    ct = vtk.vtkImageData()
    ct.SetExtent(0, 9, 0, 7, 0, 5)
    ct.SetSpacing(0.5, 0.5, 1.0)
    ct.AllocateScalars(vtk_type, 1)
    sc = ct.GetPointData().GetScalars()
    sc.SetName("density")
    for i in range(ct.GetNumberOfPoints()):
        x, y, z = ct.GetPoint(i)
        sc.SetTuple1(i, int(40 + 20 * x + 10 * y - 5 * z))
    xml_write(vtk.vtkXMLImageDataWriter, ct, os.path.join(V, name), "appended", "zlib")
    record(os.path.join(V, name), "image", VTK_TOOL, "vti %s values" % tname, "vtk-ct-" + tname, "density",
           "vtkImageData 10x8x6, %s scalars 40 + 20x + 10y - 5z; vtkXMLImageDataWriter appended zlib" % tname)
two = vtk.vtkImageData()
two.DeepCopy(img)
two.GetPointData().SetActiveScalars("s")
img_xml("wavelet-active-second.vti", two, "vtk-wavelet-s", " active scalars s (second array)", mode="appended", comp="zlib")
img_xml("wavelet-bigendian.vti", img, "vtk-wavelet-image", " big-endian", mode="appended", comp="zlib", big=True)
for pieces in [2, 4]:
    pw = vtk.vtkXMLPImageDataWriter()
    pw.SetInputData(img)
    name = "wavelet-p%d.pvti" % pieces
    pw.SetFileName(os.path.join(V, name))
    pw.SetNumberOfPieces(pieces)
    pw.SetStartPiece(0)
    pw.SetEndPiece(pieces - 1)
    assert pw.Write() == 1
    record(os.path.join(V, name), "image", VTK_TOOL, "pvti %d pieces" % pieces, "vtk-wavelet-image", "RTData",
           "the wavelet image; vtkXMLPImageDataWriter pieces=%d (default appended zlib)" % pieces)
for binary in [False, True]:
    for version in [None, 42]:
        name = "wavelet-sp-%s%s.vtk" % ("binary" if binary else "ascii", "-v42" if version else "")
        w = vtk.vtkStructuredPointsWriter()
        w.SetInputData(img)
        w.SetFileName(os.path.join(V, name))
        w.SetFileTypeToBinary() if binary else w.SetFileTypeToASCII()
        if version:
            w.SetFileVersion(version)
        assert w.Write() == 1
        record(os.path.join(V, name), "image", VTK_TOOL, "vtk legacy STRUCTURED_POINTS %s%s" % (
            "binary" if binary else "ascii", " v4.2" if version else ""), "vtk-wavelet-image", "RTData",
            "the wavelet image; vtkStructuredPointsWriter %s%s" % ("binary" if binary else "ascii", " FileVersion 42" if version else ""))
manifest.close()
