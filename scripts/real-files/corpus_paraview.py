"""The ParaView 5.11 part of the real-files corpus (run by make-corpus.sh with pvpython).

  pvpython --force-offscreen-rendering scripts/real-files/corpus_paraview.py OUT

Writes OUT/paraview/ (data saved by paraview.simple.SaveData from Wavelet, Clip, Tetrahedralize,
Append Datasets, Delaunay 3D, Resample To Image pipelines), OUT/colormaps/ (every built-in preset,
one file each, exactly the string vtkSMTransferFunctionPresets holds, as the colour map editor's
export of one preset holds it; and a few colour maps written by ParaView's own exporter,
vtkSMTransferFunctionProxy.ExportTransferFunction, with their opacity Points), and one JSON line
per file to OUT/manifest-paraview.jsonl.
"""
import os
import sys

# an extracted python3-paraview (PYTHONPATH) must win over python3-vtk9's vtkmodules
sys.path[:0] = [p for p in os.environ.get("PYTHONPATH", "").split(":") if p]
sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))  # scripts/paraview_colormaps.py

import json  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview.simple import (AppendDatasets, Clip, Delaunay3D, Elevation, ResampleToImage, SaveData,  # noqa: E402
                             Sphere, Tetrahedralize, Transform, Wavelet)
from vtkmodules.vtkCommonCore import vtkVersion  # noqa: E402

from paraview_colormaps import export_colormap  # noqa: E402

OUT = os.path.abspath(sys.argv[1])
PV = "ParaView %s (pvpython, VTK %s)" % (sm.vtkSMProxyManager.GetParaViewSourceVersion().split()[-1],
                                         vtkVersion.GetVTKVersion())
manifest = open(os.path.join(OUT, "manifest-paraview.jsonl"), "w")


def record(path, kind, fmt, family, field, how):
    manifest.write(json.dumps({"file": os.path.relpath(path, OUT), "kind": kind, "tool": PV, "format": fmt,
                               "family": family, "field": field, "how": how}) + "\n")


P = os.path.join(OUT, "paraview")
os.makedirs(P, exist_ok=True)


def save(proxy, name, kind, fmt, family, field, pipeline, **options):
    path = os.path.join(P, name)
    SaveData(path, proxy, **options)
    record(path, kind, fmt, family, field,
           "%s; SaveData(%s%s)" % (pipeline, name, "".join(", %s=%r" % kv for kv in sorted(options.items()))))


wavelet = Wavelet()
wavelet.WholeExtent = [-6, 6, -6, 6, -6, 6]
W = "Wavelet(WholeExtent -6..6)"
# images
save(wavelet, "wavelet.vti", "image", "vti (SaveData defaults)", "pv-wavelet", "RTData", W)
save(wavelet, "wavelet-lz4.vti", "image", "vti appended LZ4", "pv-wavelet", "RTData", W, CompressorType="LZ4")
save(wavelet, "wavelet-ascii.vti", "image", "vti ascii", "pv-wavelet", "RTData", W, DataMode="Ascii")
save(wavelet, "wavelet.pvti", "image", "pvti (SaveData, one process)", "pv-wavelet", "RTData", W)
save(wavelet, "wavelet.vtk", "image", "vtk legacy STRUCTURED_POINTS (VTK 9.2 writer)", "pv-wavelet", "RTData", W)
save(wavelet, "wavelet-binary.vtk", "image", "vtk legacy STRUCTURED_POINTS binary", "pv-wavelet", "RTData", W, FileType="Binary")

# tetrahedral meshes
clip = Clip(Input=wavelet)
clip.ClipType = "Plane"
clip.ClipType.Origin = [0.3, 0.2, 0.1]
clip.ClipType.Normal = [1, 0.5, 0.25]
C = W + " -> Clip(Plane origin (0.3,0.2,0.1) normal (1,0.5,0.25))"
tet = Tetrahedralize(Input=clip)
T = C + " -> Tetrahedralize"
save(tet, "clip-tets.vtu", "mesh", "vtu (SaveData defaults)", "pv-clip-tets", "RTData", T)
save(tet, "clip-tets-lz4.vtu", "mesh", "vtu appended LZ4", "pv-clip-tets", "RTData", T, CompressorType="LZ4")
save(tet, "clip-tets-lzma.vtu", "mesh", "vtu appended LZMA", "pv-clip-tets", "RTData", T, CompressorType="LZMA")
save(tet, "clip-tets-none-binary.vtu", "mesh", "vtu binary, no compression", "pv-clip-tets", "RTData", T,
     CompressorType="None", DataMode="Binary")
save(tet, "clip-tets-ascii.vtu", "mesh", "vtu ascii", "pv-clip-tets", "RTData", T, DataMode="Ascii")
save(tet, "clip-tets.pvtu", "mesh", "pvtu (SaveData, one process)", "pv-clip-tets", "RTData", T)
save(tet, "clip-tets.vtk", "mesh", "vtk legacy ascii (VTK 9.2 writer)", "pv-clip-tets", "RTData", T)
save(tet, "clip-tets-binary.vtk", "mesh", "vtk legacy binary (VTK 9.2 writer)", "pv-clip-tets", "RTData", T, FileType="Binary")
# the clip as it is (hexahedra, wedges, pyramids, tetrahedra)
save(clip, "clip-mixed.vtu", "mesh", "vtu mixed linear cells", "pv-clip-mixed", "RTData", C)
save(clip, "clip-mixed.vtk", "mesh", "vtk legacy mixed linear cells", "pv-clip-mixed", "RTData", C)
tw = Tetrahedralize(Input=wavelet)
save(tw, "wavelet-tets.vtu", "mesh", "vtu (SaveData defaults)", "pv-wavelet-tets", "RTData", W + " -> Tetrahedralize")

# Append Datasets: the two halves of the wavelet (Clip and Clip inverted, each tetrahedralised),
# adjacent along the cut with their points there repeated; and two overlapping balls
half_a = Tetrahedralize(Input=Clip(Input=wavelet, ClipType="Plane"))
half_b_clip = Clip(Input=wavelet, ClipType="Plane")
half_b_clip.Invert = 0
half_b = Tetrahedralize(Input=half_b_clip)
halves = AppendDatasets(Input=[half_a, half_b])
save(halves, "append-halves.vtu", "mesh", "vtu Append Datasets of two adjacent meshes", "pv-append-halves", "RTData",
     W + " -> Clip(plane x=0) and Clip(plane x=0, Invert off), each Tetrahedralize -> AppendDatasets")
ball = Delaunay3D(Input=Sphere(ThetaResolution=16, PhiResolution=12))
ball_e = Elevation(Input=ball)
ball_e.LowPoint = [0, 0, -0.5]
ball_e.HighPoint = [0, 0, 0.5]
moved = Transform(Input=ball_e)
moved.Transform.Translate = [0.3, 0.1, 0.0]
over = AppendDatasets(Input=[ball_e, moved])
B = "Sphere(Theta 16, Phi 12) -> Delaunay3D -> Elevation(z -0.5..0.5)"
save(ball_e, "ball.vtu", "mesh", "vtu (SaveData defaults)", "pv-ball", "Elevation", B)
save(over, "append-overlap.vtu", "mesh", "vtu Append Datasets of two overlapping balls", "pv-append-overlap", "Elevation",
     B + ", and its copy Transform-ed by (0.3,0.1,0) -> AppendDatasets (overlapping: must be refused)")
resampled = ResampleToImage(Input=ball_e)
resampled.SamplingDimensions = [12, 10, 8]
save(resampled, "ball-resampled.vti", "image", "vti (ResampleToImage, vtkValidPointMask beside the field)",
     "pv-ball-resampled", "Elevation", B + " -> ResampleToImage(12x10x8)")

# colour maps: every built-in preset as shipped, one file each
CM = os.path.join(OUT, "colormaps")
os.makedirs(os.path.join(CM, "builtin"), exist_ok=True)
presets = sm.vtkSMTransferFunctionPresets.GetInstance()
for i in range(presets.GetNumberOfPresets()):
    text = presets.GetPresetAsString(i)
    name = json.loads(text)["Name"]
    path = os.path.join(CM, "builtin", "%03d.json" % i)
    with open(path, "w") as f:
        f.write(text)
    record(path, "colormap", "ParaView built-in preset %d: %s" % (i, name), "builtin", None,
           "vtkSMTransferFunctionPresets.GetInstance().GetPresetAsString(%d)" % i)
# colour maps through the colour map editor's Export (with the opacity function's Points)
for k, (preset, log_range) in enumerate([("Viridis (matplotlib)", None), ("Cool to Warm", None), ("Jet", None),
                                         ("Black-Body Radiation", None), ("Rainbow Uniform", None),
                                         ("Inferno (matplotlib)", (0.1, 1000.0)), ("Cool to Warm", (0.1, 1000.0))]):
    path = os.path.join(CM, "exported-%d.json" % k)
    export_colormap("corpus_%d" % k, preset, log_range, "exported " + preset, path)
    record(path, "colormap", "exported %s%s" % (preset, ", log scale over [0.1, 1000]" if log_range else ""), "exported",
           None, "ApplyPreset(%r)%s; vtkSMTransferFunctionProxy.ExportTransferFunction(lut, opacity)" % (
               preset, "; RescaleTransferFunction(0.1, 1000); UseLogScale = 1" if log_range else ""))
manifest.close()
