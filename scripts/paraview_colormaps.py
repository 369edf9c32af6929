"""The colour map editor's Export as scripts/paraview-presets.py and
scripts/real-files/corpus_paraview.py use it (both run by pvpython; import this after the
PYTHONPATH entries have been put first, as those scripts do)."""
from paraview import servermanager as sm
from paraview.simple import GetColorTransferFunction, GetOpacityTransferFunction


def export_colormap(array_name, preset, log_range, export_name, path, discretize=None):
    """Applies `preset` to the colour map of `array_name` as the GUI does (its opacity function:
    ParaView's default ramp); with `log_range` (lo, hi) both are rescaled to it and UseLogScale is
    set; `discretize`, if given, sets Discretize. Then writes both with the colour map editor's
    Export (vtkSMTransferFunctionProxy.ExportTransferFunction) as `export_name` to `path`.
    Returns (colour map, opacity function)."""
    lut = GetColorTransferFunction(array_name)
    otf = GetOpacityTransferFunction(array_name)
    lut.ApplyPreset(preset, False)
    if log_range:
        lut.RescaleTransferFunction(*log_range)
        otf.RescaleTransferFunction(*log_range)
        lut.UseLogScale = 1
    if discretize is not None:
        lut.Discretize = discretize
    lut.UpdateVTKObjects()
    otf.UpdateVTKObjects()
    if not sm.vtkSMTransferFunctionProxy.ExportTransferFunction(lut.SMProxy, otf.SMProxy, export_name, path):
        raise SystemExit("ExportTransferFunction failed: " + export_name)
    return lut, otf
