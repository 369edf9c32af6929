#!/usr/bin/env python3
"""Render rayint's mesh cases with VTK's own unstructured-grid volume mappers and check the
images with `rayint check --candidate-image` (issue 18, "The real client").

Run it through scripts/vtk-render.sh (installs python3-vtk9 and xvfb when missing and gives VTK
an X display); this file needs Debian's /usr/bin/python3 with vtk (9.1) and numpy, and
matplotlib for the figures.

    /usr/bin/python3 scripts/vtk_render.py --self-check          # camera/TF translation checks only
    xvfb-run -a /usr/bin/python3 scripts/vtk_render.py --rayint build/rayint --out reports/vtk-render

What is rendered (conventions read from VTK 9.1's sources, see reports/vtk-render/README.md):

* vtkUnstructuredGridVolumeRayCastMapper (software ray caster, Bunyk traversal) with each of
  vtkUnstructuredGrid{LinearRayIntegrator, PartialPreIntegration, PreIntegration,
  HomogeneousRayIntegrator}; ImageSampleDistance 1, no automatic adjustment.
* vtkProjectedTetrahedraMapper (vtkOpenGLProjectedTetrahedraMapper: Shirley-Tuchman projected
  tetrahedra in OpenGL, float FBO).

Transfer function (the unit-distance convention of `rayint tf import --unit-distance D`):
  VTK's attenuation is ScalarOpacity(s) / ScalarOpacityUnitDistance, so the scalar opacity gets
  the nodes of rayint's density rho times D and the unit distance is D; D = 1 / max(rho) keeps
  every opacity in [0, 1] (the projected-tetrahedra mapper stores opacity in 8 bits, clamped).
  The colour function (RGB space, linear) gets a node at every breakpoint of any kappa channel
  with kappa's values there: VTK's colour is rayint's straight chromaticity kappa (emission
  kappa * rho), as src/rayint/vtk/vtk_integrators.cpp established per segment. Both hold their
  end values outside the nodes, as rayint does. The three density functions must be equal (VTK
  has one attenuation).

Camera: rayint's pixel (x, y), y down from the top, is the ray through the pixel centre
((x + 0.5)/W, (y + 0.5)/H) (geometry/camera.hpp). VTK's renderer has y up, so every read-back is
flipped to rayint's row order before it is written.
  * Projected tetrahedra: OpenGL rasterises at pixel centres, so rayint's camera maps one to one
    (position, focal point = look_at, view up = up, view angle = fov_deg; or parallel projection
    with parallel scale = ortho_height / 2).
  * Ray caster: the Bunyk traversal casts texel (i, j) (j up) at normalised device coordinate
    2i/W - 1 (the pixel's corner, not its centre), and the display helper draws the W x H texture
    over the viewport with texture coordinates running from texel centre 0 to texel centre W-1,
    bilinearly filtered: screen pixel p reads texel position (p + 0.5)(W - 1)/W. With the view
    angle widened to tan(a'/2) = tan(a/2) * W/(W - 1) and the window centre shifted by (1/W, 1/H),
    texel i lies at rayint pixel position i * W/(W - 1) and screen pixel p reconstructs exactly
    rayint's pixel centre p + 0.5 (from its two nearest texels: VTK's bilinear display filter
    remains). Square images only (one view angle serves both axes). `--camera nominal` renders
    with rayint's camera copied literally instead, to show what the half-pixel convention costs.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

INTEGRATORS = {
    "linear": "vtkUnstructuredGridLinearRayIntegrator",
    "partial_preint": "vtkUnstructuredGridPartialPreIntegration",
    "preint": "vtkUnstructuredGridPreIntegration",
    "homogeneous": "vtkUnstructuredGridHomogeneousRayIntegrator",
}


# --------------------------------------------------------------------------------------------
# rayint's conventions, written from geometry/camera.hpp and model/transfer_function.hpp

def rayint_ray(cam, px, py):
    """rayint's Camera::ray_at(px, py): the ray through pixel position (px, py), y down."""
    pos = np.array(cam["position"], float)
    fwd = np.array(cam["look_at"], float) - pos
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, np.array(cam.get("up", [0, 1, 0]), float))
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    w, h = cam["width"], cam["height"]
    u = (2.0 * px / w - 1.0) * (w / h)
    v = 1.0 - 2.0 * py / h
    if "fov_deg" in cam:
        half = math.tan(0.5 * math.radians(cam["fov_deg"]))
        d = fwd + u * half * right + v * half * up
        return pos, d / np.linalg.norm(d)
    half = 0.5 * cam["ortho_height"]
    return pos + u * half * right + v * half * up, fwd


def points_of(spec):
    """A transfer-function entry as three lists of (scalar, value) points (r, g, b)."""
    if isinstance(spec, dict):
        return [spec[c] for c in "rgb"]
    return [spec, spec, spec]


def evaluate(points, s):
    """rayint's PiecewiseLinear: linear between nodes, the end values held outside."""
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return float(np.interp(s, xs, ys))


# --------------------------------------------------------------------------------------------
# Cases: which bundled cases VTK can render exactly, and the small changes that make it so

def derived_cases(case_dir=os.path.join(ROOT, "reports", "vtk-render", "cases")):
    """The cases rendered, as (file name, case dict, what was changed). Mesh paths are rewritten
    relative to `case_dir`, where the case files are written."""
    out = []

    def load(name):
        with open(os.path.join(ROOT, "cases", name)) as f:
            return json.load(f)

    def bundled(name):
        """cases/<name>, its rays dropped, its mesh path (if any) made relative to `case_dir`."""
        case = load(name)
        del case["rays"]
        if "mesh_file" in case:
            case["mesh_file"] = os.path.relpath(os.path.join(ROOT, "cases", case["mesh_file"]), case_dir)
        return case

    def named(case, name, description):
        """A copy of `case` named `name`, described by `description` and the generator's mark."""
        c = json.loads(json.dumps(case))
        c["name"] = name
        c["description"] = description + " Generated by scripts/vtk_render.py, do not edit."
        return c

    def kappa_at_most_one(case, name, description):
        """named(case, name, description) with its colour scaled by 1/1.5, so that kappa <= 1 (VTK
        clamps colour to [0, 1] in its 8-bit image) where the bundled case reaches 1.5."""
        c = named(case, name, description)
        tf = c["transfer_function"]
        k = 1.0 / 1.5
        tf["color"] = {ch: [[s, v * k] for s, v in pts] for ch, pts in zip("rgb", points_of(tf["color"]))}
        return c

    def off_axis(case):
        """The camera moved 0.8 degrees off the ball mesh's grid axes (vtk-ball-radial-off-axis)."""
        case["camera"]["position"] = [0.031, 0.047, 4]

    def add(case, what):
        """`case` written as <its name>.json; `what` says what was changed."""
        out.append((case["name"] + ".json", case, what))

    ball = bundled("mesh-ball-radial.json")
    floor = named(ball, "vtk-floor-homogeneous",
                  "cases/mesh-ball-radial.json's mesh and camera (moved off the grid axis as in "
                  "vtk-ball-radial-off-axis) with constant density 1.5 "
                  "and constant colour (0.8, 0.5, 0.3): every VTK integrator that integrates "
                  "a homogeneous segment exactly should reproduce it up to its read-back precision.")
    floor["transfer_function"] = {"density": [[0.0, 1.5], [1.0, 1.5]],
                                  "color": {"r": [[0.0, 0.8]], "g": [[0.0, 0.5]], "b": [[0.0, 0.3]]}}
    off_axis(floor)
    add(floor, "constant rho and kappa (VTK exact up to its precision): the floor")

    ball = kappa_at_most_one(ball, "vtk-ball-radial",
                             "cases/mesh-ball-radial.json with its colour scaled by 1/1.5 so that kappa <= 1 "
                             "(VTK clamps colour to [0, 1] in its 8-bit image); rays dropped, camera kept.")
    add(ball, "mesh-ball-radial, kappa scaled by 1/1.5 (max 1.5 -> 1)")

    off = named(ball, "vtk-ball-radial-off-axis",
                "vtk-ball-radial with the camera moved off the mesh's grid axes (position "
                "[0.031, 0.047, 4] instead of [0, 0, 4]): on the axis, faces of the structured "
                "ball mesh are seen exactly edge-on, where VTK's Bunyk traversal drops rays and "
                "its partial pre-integration crashes.")
    off_axis(off)
    add(off, "vtk-ball-radial with the camera 0.8 degrees off the grid axis")

    add(kappa_at_most_one(bundled("mesh-linear-field.json"), "vtk-linear-field",
                          "cases/mesh-linear-field.json with its colour scaled by 1/1.5 so that kappa <= 1; "
                          "rays dropped, camera kept."),
        "mesh-linear-field, kappa scaled by 1/1.5 (max 1.5 -> 1)")

    cube = named(bundled("mesh-inline-cube.json"), "vtk-inline-cube",
                 "cases/mesh-inline-cube.json (kappa <= 1 already) with a camera added: "
                 "6 tets, breakpoints inside cells.")
    cube["background"] = [0.1, 0.1, 0.1]
    cube["camera"] = {"position": [2.6, 1.9, 3.1], "look_at": [0.5, 0.5, 0.5], "up": [0, 1, 0],
                      "fov_deg": 30, "width": 128, "height": 128}
    add(cube, "mesh-inline-cube with a camera (128 x 128) added")

    ortho = named(cube, "vtk-inline-cube-ortho",
                  "vtk-inline-cube seen through an orthographic camera (ortho_height 2.2) from the "
                  "same position: VTK's Bunyk traversal interpolates scalars with barycentric "
                  "weights taken in screen space, which is exact only without perspective.")
    del ortho["camera"]["fov_deg"]
    ortho["camera"]["ortho_height"] = 2.2
    add(ortho, "vtk-inline-cube with an orthographic camera")
    return out


# --------------------------------------------------------------------------------------------
# VTK side

def vtk_grid(case, case_path):
    import vtk
    if "mesh" in case:
        m = case["mesh"]
        pts = vtk.vtkPoints()
        pts.SetDataTypeToDouble()
        for p in m["points"]:
            pts.InsertNextPoint(*p)
        grid = vtk.vtkUnstructuredGrid()
        grid.SetPoints(pts)
        for t in m["tets"]:
            ids = vtk.vtkIdList()
            for k in t:
                ids.InsertNextId(k)
            grid.InsertNextCell(vtk.VTK_TETRA, ids)
        sc = vtk.vtkDoubleArray()
        sc.SetName("s")
        for v in m["scalars"]:
            sc.InsertNextValue(v)
        grid.GetPointData().SetScalars(sc)
        return grid
    path = os.path.join(os.path.dirname(case_path), case["mesh_file"])
    reader = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if case.get("scalar_field"):
        grid.GetPointData().SetActiveScalars(case["scalar_field"])
    return grid


def vtk_transfer(case, colour_nodes_at_density=True):
    """(vtkPiecewiseFunction opacity, vtkColorTransferFunction colour, unit distance D).

    With `colour_nodes_at_density` the colour function also gets a node at every density
    breakpoint (the same function: kappa is linear between its own breakpoints). That works around
    a bug of VTK 9.1's linear and partial pre-integration transfer functions
    (vtkLinearRayIntegratorTransferFunction::GetTransferFunction): their loop over the opacity's
    nodes stops when a node equals the opacity's range[0], i.e. after the FIRST node, so the
    opacity's other nodes never become control points and the attenuation is interpolated
    linearly between the colour's nodes instead."""
    import vtk
    tf = case["transfer_function"]
    dens = points_of(tf["density"])
    if not (dens[0] == dens[1] == dens[2]):
        raise SystemExit(case["name"] + ": per-channel density: VTK has one attenuation for all channels")
    rho_max = max(v for _, v in dens[0])
    unit = 1.0 / rho_max if rho_max > 0 else 1.0
    opacity = vtk.vtkPiecewiseFunction()
    for s, v in dens[0]:
        opacity.AddPoint(s, v * unit)
    cols = points_of(tf["color"])
    nodes = {p[0] for c in cols for p in c}
    if colour_nodes_at_density:
        nodes |= {p[0] for p in dens[0]}
    nodes = sorted(nodes)
    colour = vtk.vtkColorTransferFunction()
    colour.SetColorSpaceToRGB()
    for s in nodes:
        colour.AddRGBPoint(s, *(evaluate(c, s) for c in cols))
    return opacity, colour, unit


def volume_property(opacity, colour, unit):
    """The translated transfer function as a vtkVolumeProperty: linear interpolation, no shading
    (shared by this script, scripts/scaling.py and scripts/vtk/vtk_image_render.py)."""
    import vtk
    prop = vtk.vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colour)
    prop.SetScalarOpacityUnitDistance(unit)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    return prop


def tet_mapper(mapper, integrator):
    """An unstructured-grid mapper: "raycast" (the ray integrator `integrator`, one ray a pixel,
    2 threads), "zsweep" (one ray a pixel) or else projected tetrahedra."""
    import vtk
    if mapper == "raycast":
        m = vtk.vtkUnstructuredGridVolumeRayCastMapper()
        m.SetRayIntegrator(getattr(vtk, INTEGRATORS[integrator])())
        m.AutoAdjustSampleDistancesOff()
        m.SetImageSampleDistance(1.0)
        m.SetNumberOfThreads(2)
    elif mapper == "zsweep":
        m = vtk.vtkUnstructuredGridVolumeZSweepMapper()
        m.AutoAdjustSampleDistancesOff()
        m.SetImageSampleDistance(1.0)
    else:
        m = vtk.vtkProjectedTetrahedraMapper()
    return m


def offscreen_volume(m, data, prop, w, h, alpha_planes=False):
    """`data` through the mapper `m` with `prop`, as a volume in a w x h off-screen window without
    multisampling (with alpha bit planes when asked): (window, renderer, volume), the renderer in
    the window and the volume in the renderer."""
    import vtk
    m.SetInputData(data)
    vol = vtk.vtkVolume()
    vol.SetMapper(m)
    vol.SetProperty(prop)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    if alpha_planes:
        win.SetAlphaBitPlanes(1)
    win.SetSize(w, h)
    ren = vtk.vtkRenderer()
    win.AddRenderer(ren)
    ren.AddVolume(vol)
    return win, ren, vol


def vtk_camera_settings(cam, mapper, camera_mode):
    """(view angle or parallel scale, window centre) for a VTK camera equivalent to rayint's."""
    w, h = cam["width"], cam["height"]
    if mapper == "raycast" and camera_mode == "exact":
        if w != h:
            raise SystemExit("the ray caster's camera translation needs a square image")
        k = w / (w - 1.0)
        centre = (1.0 / w, 1.0 / h)
    else:
        k = 1.0
        centre = (0.0, 0.0)
    if "fov_deg" in cam:
        angle = 2.0 * math.degrees(math.atan(k * math.tan(0.5 * math.radians(cam["fov_deg"]))))
        return {"view_angle": angle, "window_centre": centre}
    return {"parallel_scale": 0.5 * cam["ortho_height"] * k, "window_centre": centre}


def make_vtk_camera(cam, settings):
    import vtk
    c = vtk.vtkCamera()
    c.SetPosition(*cam["position"])
    c.SetFocalPoint(*cam["look_at"])
    c.SetViewUp(*cam.get("up", [0, 1, 0]))
    if "view_angle" in settings:
        c.ParallelProjectionOff()
        c.SetViewAngle(settings["view_angle"])
    else:
        c.ParallelProjectionOn()
        c.SetParallelScale(settings["parallel_scale"])
    c.SetWindowCenter(*settings["window_centre"])
    c.OrthogonalizeViewUp()
    return c


def vtk_unproject(camera, aspect, ndc_x, ndc_y):
    """The world-space ray (origin, unit direction) through VTK normalised device coordinates
    (ndc_x, ndc_y), by the inverse of the projection x view matrix the Bunyk ray caster uses
    (GetProjectionTransformMatrix(aspect, 0, 1) * GetViewTransformMatrix())."""
    import vtk
    m = vtk.vtkMatrix4x4()
    vtk.vtkMatrix4x4.Multiply4x4(camera.GetProjectionTransformMatrix(aspect, 0.0, 1.0),
                                 camera.GetViewTransformMatrix(), m)
    m.Invert()
    pts = []
    for z in (0.0, 0.5):
        p = m.MultiplyPoint((ndc_x, ndc_y, z, 1.0))
        pts.append(np.array(p[:3]) / p[3])
    d = pts[1] - pts[0]
    return pts[0], d / np.linalg.norm(d)


def render(case, case_path, mapper, integrator, camera_mode, colour_nodes_at_density=True, transparent=False):
    """One VTK render; returns (rgba float array (H, W, 4) with row 0 at the TOP, info dict).
    `transparent`: the background is transparent black (alpha 0), so the frame buffer holds the
    volume's premultiplied colour and its alpha (both mappers blend with GL_ONE_MINUS_SRC_ALPHA),
    to be composited over the case's background by `rayint check --candidate-alpha premultiplied`."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    cam = case["camera"]
    w, h = cam["width"], cam["height"]
    grid = vtk_grid(case, case_path)
    opacity, colour, unit = vtk_transfer(case, colour_nodes_at_density)
    prop = volume_property(opacity, colour, unit)
    win, ren, _ = offscreen_volume(tet_mapper(mapper, integrator), grid, prop, w, h, alpha_planes=transparent)
    if transparent:
        ren.SetBackground(0.0, 0.0, 0.0)
        ren.SetBackgroundAlpha(0.0)
    else:
        ren.SetBackground(*case.get("background", [0.0, 0.0, 0.0]))
    settings = vtk_camera_settings(cam, mapper, camera_mode)
    ren.SetActiveCamera(make_vtk_camera(cam, settings))
    ren.ResetCameraClippingRange()
    win.Render()
    win.Render()  # the second frame is the one read (the first may still size buffers)
    arr = vtk.vtkFloatArray()
    win.GetRGBAPixelData(0, 0, w - 1, h - 1, 0, arr, 0)
    rgba = vtk_to_numpy(arr).astype(np.float64).reshape(h, w, 4)[::-1]  # GL rows run up
    sizes = [0, 0, 0, 0]
    try:
        win.GetColorBufferSizes(sizes)
    except TypeError:
        sizes = None
    caps = [ln.strip() for ln in win.ReportCapabilities().splitlines() if "OpenGL" in ln][:3]
    info = {"unit_distance": unit, "camera": settings, "color_buffer_bits": sizes, "opengl": caps}
    return rgba, info


# --------------------------------------------------------------------------------------------
# Self-check: the translation of the camera and of the transfer function

def self_check(verbose=True):
    """Returns the list of failures (empty: all passed)."""
    failures = []
    worst = {"raycast texel": 0.0, "raycast display": 0.0, "projected": 0.0, "tf": 0.0}
    for _, case, _ in derived_cases():
        cam = case["camera"]
        w, h = cam["width"], cam["height"]
        # Ray caster: texel (i, j) (j up) is cast at VTK NDC (2i/W - 1, 2j/H - 1) and must be rayint's
        # ray at pixel position (i W/(W-1), H - j H/(H-1)); screen pixel p reads texel position
        # (p + 0.5)(W-1)/W, i.e. rayint's pixel centre.
        c = make_vtk_camera(cam, vtk_camera_settings(cam, "raycast", "exact"))
        for i, j in [(0, 0), (w - 1, h - 1), (17, 90), (w // 2, h // 3)]:
            o, d = vtk_unproject(c, w / h, 2.0 * i / w - 1.0, 2.0 * j / h - 1.0)
            ro, rd = rayint_ray(cam, i * w / (w - 1.0), h - j * h / (h - 1.0))
            worst["raycast texel"] = max(worst["raycast texel"], np.abs(d - rd).max())
            for p in [0, 5, w - 1]:
                f = (p + 0.5) * (w - 1.0) / w  # texel position read by screen pixel p
                worst["raycast display"] = max(worst["raycast display"], abs(f * w / (w - 1.0) - (p + 0.5)))
        # Projected tetrahedra: pixel p's centre at VTK NDC (2p+1)/W - 1 is rayint's pixel centre.
        c = make_vtk_camera(cam, vtk_camera_settings(cam, "projected", "exact"))
        for x, y in [(0, 0), (w - 1, h - 1), (33, 70)]:
            o, d = vtk_unproject(c, w / h, (2.0 * x + 1) / w - 1.0, 1.0 - (2.0 * y + 1) / h)
            ro, rd = rayint_ray(cam, x + 0.5, y + 0.5)
            worst["projected"] = max(worst["projected"], np.abs(d - rd).max())
        # Transfer function: VTK's attenuation opacity/D and colour equal rho and kappa at every
        # node and between nodes.
        opacity, colour, unit = vtk_transfer(case)
        tf = case["transfer_function"]
        dens, cols = points_of(tf["density"]), points_of(tf["color"])
        for s in np.linspace(-1.0, 2.0, 601):
            worst["tf"] = max(worst["tf"], abs(opacity.GetValue(s) / unit - evaluate(dens[0], s)))
            rgb = colour.GetColor(s)
            worst["tf"] = max(worst["tf"], max(abs(rgb[k] - evaluate(cols[k], s)) for k in range(3)))
    for name, value in worst.items():
        ok = value <= 1e-12
        if verbose:
            print(f"self-check {name}: max difference {value:.3g} ({'ok' if ok else 'FAIL'})")
        if not ok:
            failures.append(name)
    return failures


def opacity_bug_demo():
    """VTK's linear integrator's attenuation at the density nodes of vtk-ball-radial, from the
    optical depth of one short constant-scalar segment, with the literal colour function (nodes at
    kappa's breakpoints only) and with the workaround (nodes at the density's too)."""
    import vtk
    case = dict(derived_cases()[1][1])
    dens = points_of(case["transfer_function"]["density"])[0]
    out = {"case": case["name"], "scalar": [s for s, _ in dens], "rho": [v for _, v in dens]}
    for mode in ("literal", "workaround"):
        opacity, colour, unit = vtk_transfer(case, mode == "workaround")
        vol = vtk.vtkVolume()
        prop = vtk.vtkVolumeProperty()
        prop.SetScalarOpacity(opacity)
        prop.SetColor(colour)
        prop.SetScalarOpacityUnitDistance(unit)
        vol.SetProperty(prop)
        rng = vtk.vtkDoubleArray()
        rng.InsertNextValue(0.0)
        rng.InsertNextValue(1.0)
        integ = vtk.vtkUnstructuredGridLinearRayIntegrator()
        integ.Initialize(vol, rng)
        got = []
        for s, _ in dens:
            arrays = [vtk.vtkDoubleArray() for _ in range(3)]
            for a, v in zip(arrays, (1e-4, s, s)):
                a.InsertNextValue(v)
            c = [0.0] * 4
            integ.Integrate(*arrays, c)
            got.append(-math.log1p(-c[3]) / 1e-4)
        out["vtk_linear_attenuation_" + mode] = got
    return out


def check_worst_pixel_ray(case, worst_case_file, tol=1e-9):
    """rayint's own ray for a worst pixel (written in the case file's description) against this
    script's rayint_ray: an independent check of rayint_ray."""
    with open(worst_case_file) as f:
        desc = json.load(f)["description"]
    import re
    m = re.search(r"pixel \((\d+), (\d+)\) of the camera, ray origin \[([^\]]*)\], direction \[([^\]]*)\]", desc)
    if not m:
        return None
    x, y = int(m.group(1)), int(m.group(2))
    o = np.array([float(t) for t in m.group(3).split(",")])
    d = np.array([float(t) for t in m.group(4).split(",")])
    ro, rd = rayint_ray(case["camera"], x + 0.5, y + 0.5)
    return max(np.abs(o - ro).max(), np.abs(d - rd).max())


# --------------------------------------------------------------------------------------------
# The report

def srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def quantisation(rgba):
    """Largest distance of the read-back values from a multiple of 1/255, and of 1/65535."""
    return (float(np.abs(rgba * 255 - np.round(rgba * 255)).max() / 255),
            float(np.abs(rgba * 65535 - np.round(rgba * 65535)).max() / 65535))


def run(args):
    import vtk
    out = os.path.relpath(args.out)  # relative paths in the committed JSON (run from the repo root)
    os.makedirs(os.path.join(out, "cases"), exist_ok=True)
    fails = self_check()
    if fails:
        raise SystemExit("self-check failed: " + ", ".join(fails))
    configs = [("raycast", k, "exact", "workaround", "opaque") for k in INTEGRATORS] + \
              [("projected", None, "exact", "workaround", "opaque")]
    if args.nominal:
        configs.append(("raycast", "linear", "nominal", "workaround", "opaque"))
    configs.append(("raycast", "linear", "exact", "literal", "opaque"))
    # Premultiplied RGBA over a transparent background, composited by rayint (check --candidate-alpha).
    configs.append(("raycast", "linear", "exact", "workaround", "transparent"))
    configs.append(("projected", None, "exact", "workaround", "transparent"))
    results = []
    summary = {"vtk_version": vtk.vtkVersion.GetVTKVersion(), "runs": results,
               "opacity_control_point_bug": opacity_bug_demo()}
    for fname, case, change in derived_cases(os.path.join(out, "cases")):
        if args.cases and case["name"] not in args.cases:
            continue
        case_path = os.path.join(out, "cases", fname)
        with open(case_path, "w") as f:
            json.dump(case, f, indent=1)
            f.write("\n")
        name = case["name"]
        cdir = os.path.join(out, name)
        os.makedirs(cdir, exist_ok=True)
        exact_npy = os.path.join(cdir, "exact.npy")
        subprocess.run([args.rayint, "render", case_path, "-o", exact_npy, "--quiet"], check=True)
        exact = np.load(exact_npy)
        bg = np.array(case.get("background", [0, 0, 0]), float)
        hit = np.any(np.abs(exact - bg) > 1e-12, axis=2)
        # Pixels whose 3 x 3 neighbourhood all hit the mesh: away from the silhouette.
        interior = hit.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                interior &= np.roll(np.roll(hit, dy, 0), dx, 1)
        interior[0, :] = interior[-1, :] = interior[:, 0] = interior[:, -1] = False
        for mapper, integrator, mode, tfmode, bgmode in configs:
            label = (f"raycast-{integrator}" if mapper == "raycast" else "projected-tetrahedra") + \
                    ("" if mode == "exact" else "-nominal-camera") + \
                    ("" if tfmode == "workaround" else "-colour-nodes-only") + \
                    ("" if bgmode == "opaque" else "-rgba-premultiplied")
            img = os.path.join(cdir, label + ".npy")
            rgba_file = os.path.join(cdir, label + ".rgba.npy")
            # Each render in its own process: a VTK crash is a result, not the end of the run.
            child = subprocess.run([sys.executable, os.path.abspath(__file__), "--render-one", case_path,
                                    mapper, str(integrator), mode, tfmode, bgmode, rgba_file],
                                   stdout=subprocess.PIPE, text=True)
            if child.returncode != 0:
                why = (f"killed by signal {-child.returncode}" if child.returncode < 0
                       else f"exit {child.returncode}")
                print(f"{name:24s} {label:34s} VTK CRASHED ({why})", flush=True)
                results.append({"case": name, "change": change, "mapper": mapper, "integrator": integrator,
                                "camera": mode, "tf": tfmode, "background": bgmode, "label": label, "crashed": why})
                continue
            info = json.loads(child.stdout.strip().splitlines()[-1])
            rgba = np.load(rgba_file)
            os.remove(rgba_file)
            np.save(img, np.ascontiguousarray(rgba if bgmode == "transparent" else rgba[:, :, :3]))
            art = os.path.join(cdir, label)
            if os.path.isdir(art):
                shutil.rmtree(art)
            os.makedirs(art)
            diff = os.path.join(art, "diff.json")
            cmd = [args.rayint, "check", case_path, "--candidate-image", img,
                   "--rel-tol", str(args.rel_tol), "--abs-tol", str(args.abs_tol),
                   "--artifacts", art, "-o", diff, "--junit", os.path.join(art, "junit.xml"),
                   "--worst", "3"] + (["--candidate-alpha", "premultiplied"] if bgmode == "transparent" else [])
            rc = subprocess.run(cmd).returncode
            if rc not in (0, 1):
                raise SystemExit(f"rayint check exited {rc}: {' '.join(cmd)}")
            with open(diff) as f:
                d = json.load(f)
            ray_check = None
            if d.get("worst_pixels") and d["worst_pixels"][0].get("case_file"):
                ray_check = check_worst_pixel_ray(case, d["worst_pixels"][0]["case_file"])
            if bgmode == "transparent":  # what rayint compared: premultiplied RGB over the background
                rgba = np.concatenate([rgba[:, :, :3] + (1 - rgba[:, :, 3:]) * bg, rgba[:, :, 3:]], axis=2)
            err = np.abs(rgba[:, :, :3] - exact)
            q255, q65535 = quantisation(rgba)
            r = {"case": name, "change": change, "mapper": mapper, "integrator": integrator,
                 "camera": mode, "tf": tfmode, "background": bgmode, "label": label, "exit": rc, "candidate": os.path.relpath(img, out),
                 "diff": os.path.relpath(diff, out), "unit_distance": info["unit_distance"],
                 "vtk_camera": info["camera"], "color_buffer_bits": info["color_buffer_bits"],
                 "opengl": info["opengl"],
                 "readback_max_distance_from_k_over_255": q255,
                 "readback_max_distance_from_k_over_65535": q65535,
                 "max_abs_interior": float(err[interior].max()) if interior.any() else None,
                 "mean_abs_interior": float(err[interior].mean()) if interior.any() else None,
                 "max_abs_silhouette": float(err[hit & ~interior].max()) if (hit & ~interior).any() else None,
                 "max_abs_background": float(err[~hit].max()) if (~hit).any() else None,
                 "alpha_min": float(rgba[:, :, 3].min()), "alpha_max": float(rgba[:, :, 3].max()),
                 "worst_pixel_ray_vs_script": ray_check,
                 "rayint": {k: d[k] for k in ("pass", "fraction_within_tolerance", "abs_error", "rel_error",
                                               "psnr_db", "failed_pixels", "pixels", "worst_pixels")}}
            results.append(r)
            print(f"{name:24s} {label:34s} exit {rc}  max abs {d['abs_error']['max']:.4g}  "
                  f"p99 rel {d['rel_error']['p99']:.4g}  PSNR {d['psnr_db']}  within {d['fraction_within_tolerance']:.4f}  "
                  f"interior max abs {r['max_abs_interior']}", flush=True)
        figure(case, cdir, exact, [r for r in results if r["case"] == name and "crashed" not in r], out)
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(summary, f, indent=1)
        f.write("\n")


def figure(case, cdir, exact, runs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(runs) + 1
    fig, axes = plt.subplots(2, n, figsize=(2.2 * n, 4.6))
    axes[0, 0].imshow(srgb(exact), interpolation="nearest")
    axes[0, 0].set_title("exact (rayint)", fontsize=7)
    axes[1, 0].axis("off")
    axes[1, 0].text(0.0, 0.5, "row 2: |VTK - exact|,\nlargest channel,\nlog10 from 1e-4 to 1\n"
                    "(rayint's own heat maps:\n<case>/<run>/error_heat_map.png)\n"
                    f"8-bit floor 2/255 = {2 / 255:.4f}", fontsize=7, va="center")
    for k, r in enumerate(runs, start=1):
        img = np.load(os.path.join(out, r["candidate"]))
        if img.shape[2] == 4:  # premultiplied RGBA: over the case's background, as rayint composites it
            img = img[:, :, :3] + (1 - img[:, :, 3:]) * np.array(case.get("background", [0, 0, 0]), float)
        axes[0, k].imshow(srgb(img), interpolation="nearest")
        axes[0, k].set_title(r["label"].replace("raycast-", "raycast\n").replace("-rgba", "\nrgba"), fontsize=7)
        err = np.abs(img - exact).max(axis=2)
        im = axes[1, k].imshow(np.log10(np.maximum(err, 1e-4)), vmin=-4, vmax=0, cmap="magma",
                               interpolation="nearest")
        axes[1, k].set_title(f"within tol {r['rayint']['fraction_within_tolerance']:.3f}, "
                             f"max {r['rayint']['abs_error']['max']:.2g}", fontsize=7)
    for a in axes.flat:
        a.set_xticks([])
        a.set_yticks([])
    fig.suptitle(case["name"], fontsize=9)
    fig.tight_layout()
    if runs:
        fig.colorbar(im, ax=axes[1, 0], location="left", fraction=0.25, label="log10 |error|")
    fig.savefig(os.path.join(os.path.dirname(cdir), case["name"] + ".png"), dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rayint", default=os.path.relpath(os.path.join(ROOT, "build", "rayint")))
    ap.add_argument("--out", default=os.path.relpath(os.path.join(ROOT, "reports", "vtk-render")))
    ap.add_argument("--cases", nargs="*", help="case names (default: all)")
    ap.add_argument("--rel-tol", type=float, default=0.01)
    ap.add_argument("--abs-tol", type=float, default=2.0 / 255.0)
    ap.add_argument("--no-nominal", dest="nominal", action="store_false",
                    help="skip the ray caster with rayint's camera copied literally")
    ap.add_argument("--self-check", action="store_true", help="only the translation checks")
    ap.add_argument("--render-one", nargs=7,
                    metavar=("CASE", "MAPPER", "INTEGRATOR", "CAMERA", "TF", "BACKGROUND", "OUT"),
                    help="(internal) one render, RGBA float64 with row 0 at the top, to OUT (.npy)")
    args = ap.parse_args()
    if args.render_one:
        case_path, mapper, integrator, mode, tfmode, bgmode, out = args.render_one
        with open(case_path) as f:
            case = json.load(f)
        rgba, info = render(case, case_path, mapper, None if integrator == "None" else integrator, mode,
                            tfmode == "workaround", bgmode == "transparent")
        np.save(out, rgba)
        print(json.dumps(info))
        return
    if args.self_check:
        sys.exit(1 if self_check() else 0)
    run(args)


if __name__ == "__main__":
    main()
