#!/usr/bin/python3
"""Regenerates the transfer-function fixtures in tests/data/tf/ (optional; needs python3-vtk9).

  /usr/bin/python3 scripts/tf-fixtures.py PARAVIEW_COLORMAPS_JSON

1. paraview-colormaps.json: six presets copied verbatim (text slices, not re-serialised) from
   ParaView's Remoting/Views/ColorMaps.json, given as the argument (a ParaView checkout).
2. exported-opacity.json: two presets with opacity "Points" [x, opacity, midpoint, sharpness],
   in the layout ParaView's colour map editor exports. ParaView is not on this machine, so the
   curves are built in VTK (vtkPiecewiseFunction.AddPoint) and their nodes read back with
   GetNodeValue; the file is written by this script.
3. vtk-eval.json: VTK 9.1's own evaluation of every preset above (vtkColorTransferFunction.GetColor
   with the preset's colour space and HSVWrap, ParaView's default HSVWrap 0 when absent;
   vtkPiecewiseFunction.GetValue for the Points), at 401 equally spaced scalars over the colour
   range plus every node: the independent oracle of tests/test_tf_import.cpp.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

try:
    import vtk
except ImportError:  # the optional dependency of this script only (README, Dependencies)
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    subprocess.run(sudo + ["apt-get", "install", "-y", "-qq", "python3-vtk9"], check=True)
    import vtk

OUT = Path(__file__).resolve().parent.parent / "tests" / "data" / "tf"
PRESETS = ["Cool to Warm", "Viridis", "Blue to Red Rainbow", "blot", "Black-Body Radiation",
           "CIELab Blue to Red"]


def preset_slices(text):
    """The text of each top-level object of ParaView's list (objects start at '  {' lines)."""
    lines = text.splitlines(keepends=True)
    out, start = {}, None
    for i, line in enumerate(lines):
        if line.rstrip() == "  {":
            start = i
        elif start is not None and line.rstrip() in ("  }", "  },"):
            body = "".join(lines[start:i]) + "  }"
            name = json.loads(body)["Name"]
            out[name] = body
            start = None
    return out


def exported_presets():
    """Two opacity curves with midpoints and sharpness, built in VTK and read back from it."""
    specs = [
        ("rayint midpoints (sharpness 0)", "RGB",
         [(0.0, 0.9, 0.1, 0.2), (0.5, 0.2, 0.8, 0.3), (1.0, 0.1, 0.3, 0.9)],
         [(0.0, 0.0, 0.25, 0.0), (0.5, 0.4, 0.75, 0.0), (0.75, 0.8, 0.5, 0.0), (1.0, 0.1, 0.5, 0.0)]),
        ("rayint sharpness", "RGB",
         [(-1.0, 0.2, 0.2, 0.9), (0.0, 0.95, 0.95, 0.95), (1.0, 0.8, 0.1, 0.1)],
         [(-1.0, 0.05, 0.5, 0.3), (-0.25, 0.6, 0.3, 0.7), (0.25, 0.2, 0.6, 1.0), (0.6, 0.9, 0.5, 0.5),
          (1.0, 0.3, 0.5, 0.0)]),
    ]
    out = []
    for name, space, rgb, pts in specs:
        f = vtk.vtkPiecewiseFunction()
        for x, y, m, s in pts:
            f.AddPoint(x, y, m, s)
        points = []
        for i in range(f.GetSize()):
            v = [0.0] * 4
            f.GetNodeValue(i, v)
            points += v
        out.append({"ColorSpace": space, "Name": name, "NanColor": [1, 1, 0],
                    "Points": points, "RGBPoints": [c for p in rgb for c in p]})
    return out


def evaluate(preset):
    ctf = vtk.vtkColorTransferFunction()
    space = preset["ColorSpace"]
    {"RGB": ctf.SetColorSpaceToRGB, "HSV": ctf.SetColorSpaceToHSV, "Lab": ctf.SetColorSpaceToLab,
     "Diverging": ctf.SetColorSpaceToDiverging}[space]()
    ctf.SetHSVWrap(int(preset.get("HSVWrap", 0)))
    p = preset["RGBPoints"]
    xs = []
    for i in range(0, len(p), 4):
        ctf.AddRGBPoint(p[i], p[i + 1], p[i + 2], p[i + 3])
        xs.append(p[i])
    lo, hi = xs[0], xs[-1]
    n = 401
    sample = sorted(set([lo + (hi - lo) * k / (n - 1) for k in range(n)] + xs))
    opacity = None
    if "Points" in preset:
        q = preset["Points"]
        pwf = vtk.vtkPiecewiseFunction()
        for i in range(0, len(q), 4):
            pwf.AddPoint(q[i], q[i + 1], q[i + 2], q[i + 3])
        opacity = [pwf.GetValue(x) for x in sample]
    return {"name": preset["Name"], "x": sample, "rgb": [list(ctf.GetColor(x)) for x in sample],
            "opacity": opacity}


def main():
    text = Path(sys.argv[1]).read_text()
    slices = preset_slices(text)
    body = ",\n".join(slices[name] for name in PRESETS)
    (OUT / "paraview-colormaps.json").write_text("[\n" + body + "\n]\n")
    exported = exported_presets()
    (OUT / "exported-opacity.json").write_text(json.dumps(exported, indent=2) + "\n")
    presets = json.loads((OUT / "paraview-colormaps.json").read_text()) + exported
    evals = {"generator": "scripts/tf-fixtures.py (do not edit)", "vtk": vtk.vtkVersion.GetVTKVersion(),
             "presets": [evaluate(p) for p in presets]}
    (OUT / "vtk-eval.json").write_text(json.dumps(evals) + "\n")


if __name__ == "__main__":
    main()
