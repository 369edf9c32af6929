#!/usr/bin/env pvpython
"""Exports ParaView's built-in colour maps and VTK's own colours for them (run by pvpython).

  scripts/paraview-presets.sh            (finds pvpython; see there)
  pvpython --force-offscreen-rendering scripts/paraview-presets.py OUT_DIR

Writes, into OUT_DIR (tests/data/tf/ by default), generated files (do not edit):

1. paraview-5.11-presets.json -- every built-in preset, in the order of
   vtkSMTransferFunctionPresets (GetNumberOfPresets / GetPresetAsString), one preset a line,
   values as ParaView holds them (re-serialised by Python's json, which keeps every double).
2. paraview-5.11-exported.json -- presets written by ParaView's own exporter
   (vtkSMTransferFunctionProxy.ExportTransferFunction, the colour map editor's "Export"), with
   the opacity Points of the opacity transfer function: one as ParaView makes a new colour map
   (the default opacity: a ramp 0 -> 1 over the range), and two with "Use log scale" on
   (UseLogScale: 1), rescaled to [0.1, 1000] first.
3. paraview-5.11-oracle.json + paraview-5.11-oracle.npy -- the colour oracle. For each continuous
   built-in preset (RGBPoints, no IndexedColors) a fresh lookup table
   (GetColorTransferFunction) gets the preset exactly as the GUI applies it
   (vtkSMTransferFunctionProxy::ApplyPreset, no rescale: ColorSpace, HSVWrap 0 unless given,
   AllowDuplicateScalars on), Discretize off (volume mappers sample the continuous function,
   vtkColorTransferFunction::GetTable), and its client-side vtkPVDiscretizableColorTransferFunction
   is asked GetColor(x) at: 801 equally spaced scalars over [first, last node], every node,
   the next double above every node (the right limit, where Lab/HSV/Diverging round-trip the
   stored colour and where duplicate scalars jump), every interval's middle, and 10 % beyond
   each end. The .npy is float64 of shape (N, 5): x, r, g, b, opacity (NaN where the preset has
   no opacity function); the JSON gives, per preset, its index in (1) or (2), the colour space
   and flags the lookup table ended with, and its rows [offset, offset + count) in the .npy.
   Exported presets are sampled the same way, with vtkPiecewiseFunction.GetValue(x) of the
   opacity function as the fifth column.
Size: about 2.8 MB of .npy for 128 presets (3,471 nodes).
"""
import os
import sys

# pvpython puts its own //lib/python3/dist-packages first; when python3-paraview is not installed
# but extracted (it conflicts with python3-vtk9, see scripts/paraview-presets.sh), the entries of
# PYTHONPATH must win over python3-vtk9's vtkmodules.
sys.path[:0] = [p for p in os.environ.get("PYTHONPATH", "").split(":") if p]

import collections  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import tempfile  # noqa: E402

import numpy as np  # noqa: E402
from paraview import servermanager as sm  # noqa: E402
from paraview.simple import GetColorTransferFunction  # noqa: E402
from paraview_colormaps import export_colormap  # noqa: E402
from vtkmodules.vtkCommonCore import vtkVersion  # noqa: E402

UNIFORM = 513


def sample_scalars(nodes):
    lo, hi = nodes[0], nodes[-1]
    xs = set(lo + (hi - lo) * k / (UNIFORM - 1) for k in range(UNIFORM))
    xs.update(nodes)
    xs.update(math.nextafter(x, math.inf) for x in nodes)
    xs.update((a + b) / 2 for a, b in zip(nodes, nodes[1:]))
    xs.update([lo - 0.1 * (hi - lo), hi + 0.1 * (hi - lo)])
    return sorted(xs)


def lut_state(lut):
    return {"ColorSpace": lut.GetProperty("ColorSpace").GetData(), "HSVWrap": int(lut.HSVWrap), "UseLogScale": int(lut.UseLogScale),
            "AllowDuplicateScalars": int(lut.AllowDuplicateScalars), "Discretize": int(lut.Discretize)}


def sample(lut, otf, nodes):
    ctf = lut.GetClientSideObject()
    pwf = otf.GetClientSideObject() if otf is not None else None
    rows = []
    for x in sample_scalars(nodes):
        rgb = [0.0, 0.0, 0.0]
        ctf.GetColor(x, rgb)
        r, g, b = rgb
        rows.append((x, r, g, b, pwf.GetValue(x) if pwf is not None else math.nan))
    return rows


class Oracle:
    """Rows of one .npy: (x, r, g, b) or, with opacity, (x, r, g, b, opacity)."""

    def __init__(self, file, columns):
        self.file, self.columns, self.rows, self.entries = file, columns, [], []

    def add(self, entry, rows):
        entry["rows"] = [len(self.rows), len(rows)]
        self.entries.append(entry)
        self.rows += [r[:len(self.columns)] for r in rows]

    def save(self, out):
        np.save(os.path.join(out, self.file), np.array(self.rows, dtype="<f8"))
        return {"file": self.file, "columns": self.columns, "presets": self.entries}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "tests", "data", "tf")
    presets_sm = sm.vtkSMTransferFunctionPresets.GetInstance()
    presets = [json.loads(presets_sm.GetPresetAsString(i)) for i in range(presets_sm.GetNumberOfPresets())]
    with open(os.path.join(out, "paraview-5.11-presets.json"), "w") as f:
        f.write("[\n" + ",\n".join(json.dumps(p) for p in presets) + "\n]\n")

    names = collections.Counter(p["Name"] for p in presets)
    tmp = tempfile.mkdtemp()
    oracle = Oracle("paraview-5.11-oracle.npy", ["x", "r", "g", "b"])
    for i, p in enumerate(presets):
        if "RGBPoints" not in p or "IndexedColors" in p:
            continue
        name = p["Name"]
        if names[name] > 1:  # ApplyPreset(name) takes the first of that name: apply a renamed copy
            name = "%s (rayint oracle %d)" % (name, i)
            path = os.path.join(tmp, "%d.json" % i)
            with open(path, "w") as f:
                json.dump([dict(p, Name=name)], f)
            presets_sm.ImportPresets(path)
        lut = GetColorTransferFunction("rayint_oracle_%d" % i)  # a fresh lookup table
        if not lut.ApplyPreset(name, False):
            raise SystemExit("ApplyPreset failed: " + name)
        lut.Discretize = 0
        lut.UpdateVTKObjects()
        ctf = lut.GetClientSideObject()
        nodes = [p["RGBPoints"][4 * k] for k in range(len(p["RGBPoints"]) // 4)]
        if ctf.GetSize() != len(nodes):
            raise SystemExit("%s: the lookup table holds %d nodes, the preset %d" % (p["Name"], ctf.GetSize(), len(nodes)))
        oracle.add({"name": p["Name"], "preset_index": i, "file": "paraview-5.11-presets.json",
                    "applied": lut_state(lut)}, sample(lut, None, nodes))

    # Presets as ParaView's exporter writes them: colour + opacity Points (+ UseLogScale).
    exported_path = os.path.join(out, "paraview-5.11-exported.json")
    exported = []
    exported_oracle = Oracle("paraview-5.11-exported-oracle.npy", ["x", "r", "g", "b", "opacity"])
    specs = [("rayint exported Viridis", "Viridis (matplotlib)", None),
             ("rayint exported log Viridis", "Viridis (matplotlib)", (0.1, 1000.0)),
             ("rayint exported log Cool to Warm", "Cool to Warm", (0.1, 1000.0))]
    for k, (export_name, preset, log_range) in enumerate(specs):
        path = os.path.join(tmp, "export%d.json" % k)
        lut, otf = export_colormap("rayint_export_%d" % k, preset, log_range, export_name, path, discretize=0)
        with open(path) as f:
            e = json.load(f)[0]
        exported.append(e)
        nodes = [e["RGBPoints"][4 * j] for j in range(len(e["RGBPoints"]) // 4)]
        state = lut_state(lut)
        state["OpacityUseLogScale"] = int(otf.UseLogScale) if otf.GetProperty("UseLogScale") else None
        exported_oracle.add({"name": export_name, "preset_index": k, "file": "paraview-5.11-exported.json",
                    "applied": state}, sample(lut, otf, nodes))
    with open(exported_path, "w") as f:
        f.write("[\n" + ",\n".join(json.dumps(p) for p in exported) + "\n]\n")

    meta = {"generator": "scripts/paraview-presets.py (do not edit)",
            "paraview": sm.vtkSMProxyManager.GetParaViewSourceVersion(),
            "vtk": vtkVersion.GetVTKVersion(),
            "sampling": "%d equally spaced over [first, last node], every node, the next double above every "
                        "node, every interval's middle, 10%% beyond each end" % UNIFORM,
            "built_in": oracle.save(out), "exported": exported_oracle.save(out)}
    with open(os.path.join(out, "paraview-5.11-oracle.json"), "w") as f:
        f.write(json.dumps(meta, indent=1) + "\n")


if __name__ == "__main__":
    main()
