#!/usr/bin/env python3
"""Render `.vti` volumes with VTK's three image volume mappers, read the images back as floats,
gate them with `rayint check --candidate-image` against rayint's exact trilinear image and
measure how their error converges with the sample distance (`rayint converge --command`).
Issue 32. Optional: run it through scripts/vtk-image-render.sh (installs python3-vtk9 and xvfb
when missing and gives VTK an X display).

Interpreter: Debian's /usr/bin/python3 with python3-vtk9 (VTK 9.1.0), as scripts/vtk_render.py.
ParaView 5.11 is on this machine but without `pvpython` (only pvbatch/pvtkpython, VTK 9.2 inside
ParaView's own Python); one VTK with numpy, the same as the unstructured report, keeps the two
reports comparable and needs no new package.

    /usr/bin/python3 scripts/vtk/vtk_image_render.py self-check           # TF/camera checks, no display
    xvfb-run -a /usr/bin/python3 scripts/vtk/vtk_image_render.py run --rayint build/rayint \
        --out reports/vtk-image-render                                      # everything
    xvfb-run -a /usr/bin/python3 scripts/vtk/vtk_image_render.py render --scene S.json \
        --mapper gpu --step 0.25 --out img.npy                              # one image (converge's command)

Mappers (`--mapper`):
  fixedpoint          vtkFixedPointVolumeRayCastMapper, its own ray-cast image (15-bit fixed point,
                      premultiplied RGBA, read from GetRayCastImage().GetImage() in memory)
  fixedpoint-display  the same mapper's displayed frame: the ray-cast image drawn by
                      vtkOpenGLRayCastImageDisplayHelper into a float32 colour buffer
                      (vtkFramebufferPass with ColorFormat Float32, downloaded as float)
  gpu                 vtkGPUVolumeRayCastMapper (vtkOpenGLGPUVolumeRayCastMapper on Mesa llvmpipe)
  smart               vtkSmartVolumeMapper (default render mode; it picks the GPU mapper here)

Float read-back of the GPU mappers. VTK 9.1's GPU mapper does not draw into a vtkFramebufferPass
(measured: the float colour texture keeps the background), and the window's colour buffer has
8 bits. So the frame is rendered three times over a transparent black background, the shader's
final colour (float32 in the fragment shader) replaced at `//VTK::RenderToImage::Exit` by its
base-255 digits: pass k writes floor(fract(c 255^k) 255)/255 (k = 0, 1) and fract(c 255^2),
exactly representable in 8 bits for k < 2; c = sum_k digit_k / 255^k recovers the premultiplied
colour and alpha to ~3e-8 (self-check: the decoded image rounded to 8 bits equals the ordinary
8-bit read-back in every pixel). The background is composited afterwards in double:
I = C + (1 - A) * background, which is what VTK's blend (GL_ONE, GL_ONE_MINUS_SRC_ALPHA) computes.

Translation (rayint scene -> VTK), read from VTK 9.1's sources:
  * opacity: VTK's ray casters correct the scalar opacity for the sample distance d,
    alpha_d = 1 - (1 - alpha)^(d / D), D = ScalarOpacityUnitDistance. That is the opacity of a
    step of length d through extinction sigma = -ln(1 - alpha) / D, so alpha(s) = 1 - exp(-sigma(s) D)
    at nodes: every breakpoint of sigma and kappa plus OPACITY_NODES uniform scalars (alpha is
    interpolated linearly between nodes, sigma is; the mismatch is measured by the self-check).
    D = 1 world unit.
  * colour: VTK's colour is straight (not premultiplied): each sample adds T alpha_d kappa, so the
    colour function is rayint's kappa (emission g = kappa sigma), nodes at every breakpoint.
  * interpolation linear (trilinear), ShadeOff, DisableGradientOpacityOn, AutoAdjustSampleDistances
    off, jittering off (GPU), ImageSampleDistance 1 (FixedPoint), LockSampleDistanceToInputSpacing
    off (GPU; Smart has no such switch in 9.1 and its SampleDistance is forwarded, see report).
  * camera: both mappers cast through pixel centres (the GPU mapper rasterises the bounding box;
    FixedPoint's ComputeRayInfo adds 1/W to the pixel's NDC corner), so rayint's camera maps one to
    one (scripts/vtk_render.py's `projected` settings). Self-check: unprojected VTK rays at the
    pixel centres equal rayint's Camera::ray_at(x + 0.5, y + 0.5).
"""
import argparse
import ctypes
import json
import math
import os
import shlex
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
import vtk_render as vr  # noqa: E402  (scripts/vtk_render.py: camera helpers shared with it)

MAPPERS = ["fixedpoint", "fixedpoint-display", "gpu", "smart"]
OPACITY_NODES = 1024
UNIT_DISTANCE = 1.0
SIZE = 64
# sample distances of the convergence runs (world units; the volumes' spacing is 0.5)
STEPS = [2.0, 1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125]


# --------------------------------------------------------------------------------------------
# Volumes and scenes

def smooth_field(dims, spacing, origin):
    """A smooth analytic field in [0, 1]: a product of sines plus a Gaussian bump (issue 32's
    41 x 37 x 33, spacing 0.5)."""
    x = origin[0] + spacing * np.arange(dims[0])
    y = origin[1] + spacing * np.arange(dims[1])
    z = origin[2] + spacing * np.arange(dims[2])
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    s = 0.45 + 0.3 * np.sin(0.45 * X + 0.3) * np.cos(0.35 * Y - 0.2) * np.sin(0.4 * Z + 0.7)
    s += 0.25 * np.exp(-((X - 2.0) ** 2 + (Y + 1.0) ** 2 + (Z - 0.5) ** 2) / 8.0)
    return np.clip(s, 0.0, 1.0)


# 3-D Shepp-Logan head phantom (Kak & Slaney's ellipsoids, as in the "modified" 3-D phantom):
# (value, a, b, c, x0, y0, z0, phi degrees)
SHEPP_LOGAN = [
    (1.0, 0.69, 0.92, 0.81, 0.0, 0.0, 0.0, 0.0),
    (-0.8, 0.6624, 0.874, 0.78, 0.0, -0.0184, 0.0, 0.0),
    (-0.2, 0.11, 0.31, 0.22, 0.22, 0.0, 0.0, -18.0),
    (-0.2, 0.16, 0.41, 0.28, -0.22, 0.0, 0.0, 18.0),
    (0.1, 0.21, 0.25, 0.41, 0.0, 0.35, -0.15, 0.0),
    (0.1, 0.046, 0.046, 0.05, 0.0, 0.1, 0.25, 0.0),
    (0.1, 0.046, 0.046, 0.05, 0.0, -0.1, 0.25, 0.0),
    (0.1, 0.046, 0.023, 0.05, -0.08, -0.605, 0.0, 0.0),
    (0.1, 0.023, 0.023, 0.02, 0.0, -0.606, 0.0, 0.0),
    (0.1, 0.023, 0.046, 0.02, 0.06, -0.605, 0.0, 0.0),
]


def head_phantom(dims):
    """A CT-like head: the 3-D Shepp-Logan phantom on `dims` points over [-1, 1]^3, skull 1,
    brain 0.2, ventricles 0, lesions 0.3, smoothed once by [1 2 1]/4 along each axis (a CT's
    partial-volume blur). No VTK example dataset (headsq, FullHead) is on this machine."""
    g = [np.linspace(-1, 1, n) for n in dims]
    Z, Y, X = np.meshgrid(g[2], g[1], g[0], indexing="ij")
    v = np.zeros(Z.shape)
    for val, a, b, c, x0, y0, z0, phi in SHEPP_LOGAN:
        p = math.radians(phi)
        xr = (X - x0) * math.cos(p) + (Y - y0) * math.sin(p)
        yr = -(X - x0) * math.sin(p) + (Y - y0) * math.cos(p)
        v[(xr / a) ** 2 + (yr / b) ** 2 + ((Z - z0) / c) ** 2 <= 1.0] += val
    for axis in range(3):
        pad = np.pad(v, [(1, 1) if k == axis else (0, 0) for k in range(3)], mode="edge")
        sl = [slice(None)] * 3
        parts = []
        for off in (0, 1, 2):
            sl[axis] = slice(off, off + v.shape[axis])
            parts.append(pad[tuple(sl)])
        v = 0.25 * parts[0] + 0.5 * parts[1] + 0.25 * parts[2]
    return np.clip(v, 0.0, 1.0)


def write_vti(path, values, spacing, origin):
    """values[z][y][x] -> a VTK XML image (float64 point scalars 'scalar', raw appended)."""
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk
    nz, ny, nx = values.shape
    img = vtk.vtkImageData()
    img.SetDimensions(nx, ny, nz)
    img.SetSpacing(spacing, spacing, spacing)
    img.SetOrigin(*origin)
    arr = numpy_to_vtk(np.ascontiguousarray(values.ravel(), dtype=np.float64), deep=1)
    arr.SetName("scalar")
    img.GetPointData().SetScalars(arr)
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(img)
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()
    w.SetCompressorTypeToNone()
    if not w.Write():
        raise SystemExit(path + ": vtkXMLImageDataWriter failed")


def camera_for(centre, distance, fov=30.0):
    # slightly off every axis: no pixel ray lies exactly in a grid plane
    d = np.array([0.43, 0.31, 0.85])
    d /= np.linalg.norm(d)
    pos = np.array(centre) + distance * d
    return {"position": [float(v) for v in pos], "look_at": [float(v) for v in centre],
            "up": [0, 1, 0], "fov_deg": fov, "width": SIZE, "height": SIZE}


def scenes(out_dir):
    """Writes the volumes and scenes; returns {name: (scene path, description)}."""
    os.makedirs(out_dir, exist_ok=True)
    made = {}
    bg = {"color": [0.15, 0.2, 0.3]}
    effects = ["absorption", "emission"]

    dims, sp = (41, 37, 33), 0.5
    origin = [-0.5 * sp * (n - 1) for n in dims]
    write_vti(os.path.join(out_dir, "smooth.vti"), smooth_field(dims, sp, origin), sp, origin)
    smooth = {"description": "smooth analytic field (sines x Gaussian bump), 41 x 37 x 33 points, spacing 0.5; "
                             "written by scripts/vtk/vtk_image_render.py, do not edit",
              "medium": {"type": "grid", "grid_file": "smooth.vti", "array": "scalar"},
              "transfer": {"extinction": [[0.0, 0.0], [0.3, 0.05], [0.55, 0.45], [0.8, 0.25], [1.0, 0.6]],
                           "emission": {"r": [[0.0, 0.9], [0.5, 0.3], [1.0, 1.0]],
                                        "g": [[0.0, 0.2], [0.6, 0.8], [1.0, 0.5]],
                                        "b": [[0.0, 0.1], [1.0, 0.9]]}},
              "background": bg, "camera": camera_for([0, 0, 0], 42.0), "effects": effects}
    made["smooth"] = smooth

    hd = (48, 48, 40)
    hsp = 0.5
    horigin = [-0.5 * hsp * (n - 1) for n in hd]
    write_vti(os.path.join(out_dir, "head.vti"), head_phantom(hd), hsp, horigin)
    head = {"description": "CT-like head: 3-D Shepp-Logan phantom, 48 x 48 x 40 points, spacing 0.5, one [1 2 1]/4 "
                           "blur; bone-like transfer function; written by scripts/vtk/vtk_image_render.py, do not edit",
            "medium": {"type": "grid", "grid_file": "head.vti", "array": "scalar"},
            "transfer": {"extinction": [[0.0, 0.0], [0.1, 0.0], [0.15, 0.05], [0.25, 0.1], [0.4, 1.0], [0.6, 2.0], [1.0, 3.0]],
                         "emission": {"r": [[0.0, 0.6], [0.25, 0.85], [0.6, 0.9], [1.0, 1.0]],
                                      "g": [[0.0, 0.2], [0.25, 0.35], [0.6, 0.8], [1.0, 0.95]],
                                      "b": [[0.0, 0.1], [0.25, 0.25], [0.6, 0.6], [1.0, 0.9]]}},
            "background": bg, "camera": camera_for([0, 0, 0], 34.0), "effects": effects}
    made["head"] = head

    cdims = (13, 11, 9)
    corigin = [-0.5 * sp * (n - 1) for n in cdims]
    write_vti(os.path.join(out_dir, "constant.vti"), np.full(cdims[::-1], 0.5), sp, corigin)
    const = {"description": "translation check: constant scalar 0.5 on 13 x 11 x 9 points (spacing 0.5), constant "
                            "extinction 0.7 and colour (0.8, 0.5, 0.3): I = kappa (1 - e^{-sigma L}) + B e^{-sigma L} "
                            "in closed form; written by scripts/vtk/vtk_image_render.py, do not edit",
             "medium": {"type": "grid", "grid_file": "constant.vti", "array": "scalar"},
             "transfer": {"extinction": [[0.0, 0.7], [1.0, 0.7]],
                          "emission": {"r": [[0.0, 0.8]], "g": [[0.0, 0.5]], "b": [[0.0, 0.3]]}},
             "background": bg, "camera": camera_for([0, 0, 0], 16.0), "effects": effects}
    made["constant"] = const

    paths = {}
    for name, sc in made.items():
        p = os.path.join(out_dir, name + ".json")
        with open(p, "w") as f:
            json.dump(sc, f, indent=1)
            f.write("\n")
        paths[name] = p
    return paths


# --------------------------------------------------------------------------------------------
# Transfer function translation

def pl_points(spec):
    """rayint's piecewise-linear entry -> list of 3 point lists (r, g, b)."""
    if isinstance(spec, dict):
        return [spec[c] for c in "rgb"]
    return [spec, spec, spec]


def vtk_transfer(scene):
    """(vtkPiecewiseFunction opacity, vtkColorTransferFunction colour, unit distance, nodes)."""
    import vtk
    tf = scene["transfer"]
    sig = pl_points(tf["extinction"])
    if not (sig[0] == sig[1] == sig[2]):
        raise SystemExit("VTK has one opacity: the scene's extinction must be grey")
    sig = sig[0]
    kap = pl_points(tf["emission"])
    lo = min(p[0] for pts in [sig] + kap for p in pts)
    hi = max(p[0] for pts in [sig] + kap for p in pts)
    lo, hi = min(lo, 0.0), max(hi, 1.0)
    nodes = sorted(set([p[0] for p in sig] + [p[0] for pts in kap for p in pts] +
                       list(np.linspace(lo, hi, OPACITY_NODES + 1))))
    opacity = vtk.vtkPiecewiseFunction()
    for s in nodes:
        opacity.AddPoint(s, 1.0 - math.exp(-vr.evaluate(sig, s) * UNIT_DISTANCE))
    colour = vtk.vtkColorTransferFunction()
    colour.SetColorSpaceToRGB()
    for s in sorted(set([p[0] for pts in kap for p in pts] + [p[0] for p in sig] + [lo, hi])):
        colour.AddRGBPoint(s, *(vr.evaluate(c, s) for c in kap))
    return opacity, colour, UNIT_DISTANCE, (lo, hi)


def self_check(paths, verbose=True):
    """Translation checks that need no display. Returns (failures, figures)."""
    failures, figs = [], {}
    worst_sigma = worst_kappa = worst_ray = 0.0
    for name, p in paths.items():
        with open(p) as f:
            sc = json.load(f)
        opacity, colour, D, (lo, hi) = vtk_transfer(sc)
        sig = pl_points(sc["transfer"]["extinction"])[0]
        kap = pl_points(sc["transfer"]["emission"])
        for s in np.linspace(lo, hi, 4001):
            a = opacity.GetValue(s)
            worst_sigma = max(worst_sigma, abs(-math.log(1.0 - a) / D - vr.evaluate(sig, s)))
            c = colour.GetColor(s)
            worst_kappa = max(worst_kappa, max(abs(c[i] - vr.evaluate(kap[i], s)) for i in range(3)))
        cam = sc["camera"]
        c = vr.make_vtk_camera(cam, vr.vtk_camera_settings(cam, "projected", "exact"))
        w, h = cam["width"], cam["height"]
        for x, y in [(0, 0), (w - 1, h - 1), (17, 90), (w // 2, h // 3)]:
            # VTK pixel (x, j) with j up has its centre at NDC (2(x + 0.5)/W - 1, 2(j + 0.5)/H - 1);
            # rayint's row y = H - 1 - j.
            j = h - 1 - y
            o, d = vr.vtk_unproject(c, w / h, 2.0 * (x + 0.5) / w - 1.0, 2.0 * (j + 0.5) / h - 1.0)
            ro, rd = vr.rayint_ray(cam, x + 0.5, y + 0.5)
            # same line: direction equal, origin on rayint's ray
            off = (o - ro) - np.dot(o - ro, rd) * rd
            worst_ray = max(worst_ray, float(np.abs(d - rd).max()), float(np.abs(off).max()))
    figs = {"sigma_from_vtk_opacity_max_abs": worst_sigma, "kappa_from_vtk_colour_max_abs": worst_kappa,
            "pixel_centre_ray_max_abs": worst_ray}
    if worst_sigma > 1e-5:
        failures.append("opacity nodes: -ln(1 - alpha)/D differs from sigma by %.3g" % worst_sigma)
    if worst_kappa > 1e-6:
        failures.append("colour: differs from kappa by %.3g" % worst_kappa)
    if worst_ray > 1e-9:
        failures.append("camera: VTK pixel-centre ray differs from rayint's by %.3g" % worst_ray)
    if verbose:
        for k, v in figs.items():
            print("self-check %-36s %.3g" % (k, v))
        print("self-check:", "PASS" if not failures else "FAIL: " + "; ".join(failures))
    return failures, figs


# --------------------------------------------------------------------------------------------
# Rendering

def read_vti(path):
    import vtk
    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def make_mapper(mapper, step, info):
    """The VTK volume mapper named `mapper` (MAPPERS), its sample distance fixed at `step` (None:
    the mapper's default, recorded in info["default_sample_distance"]) and never adjusted by VTK."""
    import vtk
    if mapper.startswith("fixedpoint"):
        m = vtk.vtkFixedPointVolumeRayCastMapper()
    elif mapper == "gpu":
        m = vtk.vtkGPUVolumeRayCastMapper()
    elif mapper == "smart":
        m = vtk.vtkSmartVolumeMapper()
    else:
        raise SystemExit("--mapper: one of " + ", ".join(MAPPERS))
    info["default_sample_distance"] = m.GetSampleDistance()
    m.AutoAdjustSampleDistancesOff()
    if mapper == "smart":
        m.SetRequestedRenderModeToDefault()
        m.InteractiveAdjustSampleDistancesOff()
    else:  # the two ray casters
        m.LockSampleDistanceToInputSpacingOff()
    if mapper.startswith("fixedpoint"):
        m.SetImageSampleDistance(1.0)
        m.SetNumberOfThreads(2)
    elif mapper == "gpu":
        m.UseJitteringOff()
    if step is not None:
        m.SetSampleDistance(step)
    return m


def build(scene, scene_path, mapper, step):
    """(render window, renderer, volume, mapper object, info) set up for one render."""
    import vtk
    cam = scene["camera"]
    w, h = cam["width"], cam["height"]
    image = read_vti(os.path.join(os.path.dirname(os.path.abspath(scene_path)), scene["medium"]["grid_file"]))
    opacity, colour, unit, _ = vtk_transfer(scene)
    prop = vr.volume_property(opacity, colour, unit)
    prop.DisableGradientOpacityOn()
    info = {"mapper": mapper, "requested_step": step, "unit_distance": unit}
    m = make_mapper(mapper, step, info)
    m.SetBlendModeToComposite()
    win, ren, vol = vr.offscreen_volume(m, image, prop, w, h, alpha_planes=True)
    ren.SetActiveCamera(vr.make_vtk_camera(cam, vr.vtk_camera_settings(cam, "projected", "exact")))
    ren.ResetCameraClippingRange()
    return win, ren, vol, m, info


def fixedpoint_image(m, w, h):
    """FixedPoint's own ray-cast image as premultiplied RGBA float64 (h, w, 4), rows top-down:
    15-bit values / 32767 (VTKKW_FP_SCALE), placed at ImageOrigin in the viewport."""
    rc = m.GetRayCastImage()
    ptr = rc.GetImage()  # '_<hex address>_p_void'
    addr = int(ptr.split("_")[1], 16)
    mem = rc.GetImageMemorySize()
    use = rc.GetImageInUseSize()
    org = rc.GetImageOrigin()
    vps = rc.GetImageViewportSize()
    if rc.GetImageSampleDistance() != 1.0 or tuple(vps) != (w, h):
        raise SystemExit("fixedpoint: ray-cast image sample distance %g, viewport %s (expected 1, %dx%d)"
                         % (rc.GetImageSampleDistance(), vps, w, h))
    buf = (ctypes.c_uint16 * (mem[0] * mem[1] * 4)).from_address(addr)
    raw = np.frombuffer(buf, dtype=np.uint16).reshape(mem[1], mem[0], 4).astype(np.float64) / 32767.0
    out = np.zeros((h, w, 4))
    out[org[1]:org[1] + use[1], org[0]:org[0] + use[0]] = raw[:use[1], :use[0]]
    return out[::-1].copy()


def gpu_float_frame(win, vol, w, h):
    """Premultiplied RGBA float64 (h, w, 4), rows top-down, by three digit passes (module doc).
    Returns (rgba, ordinary 8-bit read-back as float in [0, 255])."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    sp = vol.GetShaderProperty()

    def grab():
        win.Render()
        arr = vtk.vtkUnsignedCharArray()
        win.GetRGBACharPixelData(0, 0, w - 1, h - 1, 0, arr, 0)
        return vtk_to_numpy(arr).reshape(h, w, 4).astype(np.float64)[::-1]

    sp.ClearAllFragmentShaderReplacements()
    win.Render()  # the first frame builds the tables and shaders; the frames compared are later ones
    plain = grab()
    digits = []
    for k in range(3):
        sp.ClearAllFragmentShaderReplacements()
        scale = 255.0 ** k
        if k < 2:
            body = "gl_FragData[0] = floor(fract(g_fragColor * %.1f) * 255.0) / 255.0;" % scale
        else:
            body = "gl_FragData[0] = fract(g_fragColor * %.1f);" % scale
        sp.AddFragmentShaderReplacement("//VTK::RenderToImage::Exit", True,
                                        "//VTK::RenderToImage::Exit\n  " + body + "\n", False)
        digits.append(grab())
    sp.ClearAllFragmentShaderReplacements()
    rgba = digits[0] / 255.0 + digits[1] / 255.0 ** 2 + digits[2] / 255.0 ** 3
    return rgba, plain


def float_fbo_frame(win, ren, bg, w, h):
    """The displayed frame in a float32 colour buffer (vtkFramebufferPass), RGB over `bg`."""
    import vtk
    ren.SetBackground(*bg)
    ren.SetBackgroundAlpha(1.0)
    fbp = vtk.vtkFramebufferPass()
    fbp.SetDelegatePass(vtk.vtkRenderStepsPass())
    fbp.SetColorFormat(vtk.vtkTextureObject.Float32)
    ren.SetPass(fbp)
    win.Render()
    win.Render()
    out = np.zeros((h, w, 4), np.float32)
    if not fbp.GetColorTexture().Download().Download2D(vtk.VTK_FLOAT, out, [w, h], 4, [0, 0]):
        raise SystemExit("fixedpoint-display: could not download the float colour texture")
    return out.astype(np.float64)[::-1].copy()


def render(scene_path, mapper, step):
    """(rgb float64 (h, w, 3) rows top-down over the scene's background, info)."""
    with open(scene_path) as f:
        scene = json.load(f)
    cam = scene["camera"]
    w, h = cam["width"], cam["height"]
    bg = np.array(scene.get("background", {}).get("color", [0, 0, 0]), float)
    win, ren, vol, m, info = build(scene, scene_path, mapper, step)
    t0 = time.time()
    if mapper == "fixedpoint-display":
        rgb = float_fbo_frame(win, ren, bg, w, h)[:, :, :3]
    else:
        ren.SetBackground(0.0, 0.0, 0.0)
        ren.SetBackgroundAlpha(0.0)
        if mapper == "fixedpoint":
            win.Render()
            rgba = fixedpoint_image(m, w, h)
        else:
            rgba, plain = gpu_float_frame(win, vol, w, h)
            info["digit_decode_vs_8bit_max"] = float(np.abs(np.round(rgba * 255.0) - plain).max())
            info["digit_decode_vs_8bit_max_abs"] = float(np.abs(rgba - plain / 255.0).max())
        rgb = rgba[:, :, :3] + (1.0 - rgba[:, :, 3:]) * bg
        info["alpha_max"] = float(rgba[:, :, 3].max())
    info["seconds"] = time.time() - t0
    # the mapper's SampleDistance after the render (Smart's echoes the request; whether its internal
    # GPU mapper uses it shows in converge's invariance, see the report)
    info["sample_distance_used"] = m.GetSampleDistance()
    if mapper == "smart":
        info["last_used_render_mode"] = {0: "default", 1: "ray cast", 2: "GPU", 4: "OSPRay"}.get(
            m.GetLastUsedRenderMode(), str(m.GetLastUsedRenderMode()))
    caps = [ln.strip() for ln in win.ReportCapabilities().splitlines() if "OpenGL" in ln][:3]
    info["opengl"] = caps
    return rgb, info


# --------------------------------------------------------------------------------------------
# The run

def sh(cmd, **kw):
    print("+", " ".join(shlex.quote(c) for c in cmd), file=sys.stderr, flush=True)
    return subprocess.run(cmd, **kw)


def closed_form_constant(scene, scene_path):
    """The exact image of the constant scene from its chord lengths (no rayint involved)."""
    image = read_vti(os.path.join(os.path.dirname(os.path.abspath(scene_path)), scene["medium"]["grid_file"]))
    b = image.GetBounds()
    lo = np.array(b[0::2])
    hi = np.array(b[1::2])
    cam = scene["camera"]
    sigma = scene["transfer"]["extinction"][0][1]
    kap = np.array([scene["transfer"]["emission"][c][0][1] for c in "rgb"])
    bg = np.array(scene["background"]["color"])
    out = np.zeros((cam["height"], cam["width"], 3))
    for y in range(cam["height"]):
        for x in range(cam["width"]):
            o, d = vr.rayint_ray(cam, x + 0.5, y + 0.5)
            with np.errstate(divide="ignore", invalid="ignore"):
                t1 = (lo - o) / d
                t2 = (hi - o) / d
            tn = np.nanmax(np.minimum(t1, t2))
            tf = np.nanmin(np.maximum(t1, t2))
            L = max(0.0, tf - max(tn, 0.0))
            T = math.exp(-sigma * L)
            out[y, x] = kap * (1 - T) + bg * T
    return out


def run(args):
    out = os.path.abspath(args.out)
    vol_dir = os.path.join(out, "scenes")
    paths = scenes(vol_dir)
    failures, figs = self_check(paths)
    rayint = os.path.abspath(args.rayint)
    me = os.path.abspath(__file__)
    results = {"vtk": None, "self_check": figs, "self_check_failures": failures, "scenes": {}, "steps": STEPS,
               "tolerance": {"abs": args.abs_tol, "rel": args.rel_tol}, "gate_size": args.gate_size}
    if args.merge and os.path.exists(os.path.join(out, "results.json")):
        with open(os.path.join(out, "results.json")) as f:
            results["scenes"] = json.load(f)["scenes"]  # the other scenes of an earlier run
    import vtk
    results["vtk"] = vtk.vtkVersion.GetVTKVersion()
    mappers = args.mappers.split(",")
    for name in args.scenes.split(","):
        sp = paths[name]
        sdir = os.path.join(out, name)
        os.makedirs(sdir, exist_ok=True)
        exact = os.path.join(sdir, "exact.npy")
        t0 = time.time()
        sh([rayint, "render", sp, "-o", exact, "-q", "--threads", "2"], check=True)
        entry = {"scene": os.path.relpath(sp, out), "exact_seconds": time.time() - t0, "mappers": {}}
        if name == "constant":
            with open(sp) as f:
                cf = closed_form_constant(json.load(f), sp)
            entry["exact_vs_closed_form_max_abs"] = float(np.abs(np.load(exact)[:, :, :3] - cf).max())
        bgc = np.array(json.load(open(sp))["background"]["color"])
        for mapper in mappers:
            r = {}
            mdir = os.path.join(sdir, mapper)
            os.makedirs(mdir, exist_ok=True)
            cand = os.path.join(mdir, "default.npy")
            # defaults: the mapper's own SampleDistance (no --step)
            p = sh([sys.executable, me, "render", "--scene", sp, "--mapper", mapper, "--out", cand,
                    "--info", os.path.join(mdir, "default-info.json")])
            if p.returncode != 0:
                r["failed"] = "render exited with status %d" % p.returncode
                entry["mappers"][mapper] = r
                continue
            with open(os.path.join(mdir, "default-info.json")) as f:
                r["default_info"] = json.load(f)
            e = np.load(exact)[:, :, :3]
            c = np.load(cand)[:, :, :3]
            err = np.abs(c - e).max(axis=2)
            r["default_error"] = {"median": float(np.median(err)), "p95": float(np.percentile(err, 95)),
                                  "max": float(err.max()),
                                  "mean_signed_rgb": [float(v) for v in (c - e).reshape(-1, 3).mean(axis=0)]}
            if name == "constant":
                r["default_vs_closed_form_max_abs"] = float(np.abs(c - cf).max())
            # silhouette: pixels the exact image covers but the candidate leaves at the background
            hit = np.abs(e - bgc).max(axis=2) > 1e-6
            missed = hit & (np.abs(c - bgc).max(axis=2) < 1e-9)
            r["pixels_hit_exact"] = int(hit.sum())
            r["pixels_dropped"] = int(missed.sum())
            # convergence over the sample distance (exact trilinear image as the expected one)
            conv = os.path.join(mdir, "converge.json")
            steps = ",".join(repr(s) for s in STEPS)
            template = "%s %s render --scene %s --mapper %s --step {step} --out {out}" % (
                shlex.quote(sys.executable), shlex.quote(me), shlex.quote(sp), mapper)
            cv = sh([rayint, "converge", sp, "--steps", steps, "--command", template, "--out-ext", ".npy",
                     "--threads", "2", "--worst", "5", "-o", conv] + (
                        ["--error-map-dir", os.path.join(mdir, "maps")] if args.error_maps else []),
                    capture_output=True, text=True)
            r["converge_exit"] = cv.returncode
            if cv.returncode not in (0, 1):
                r["converge_error"] = cv.stderr.strip()
            entry["mappers"][mapper] = r
            results["scenes"][name] = entry
            with open(os.path.join(out, "results.json"), "w") as f:
                json.dump(results, f, indent=1)
        results["scenes"][name] = entry
    # The gate: `rayint check` against the 50-digit reference image (reference/poly_reference on the
    # trilinear cubics), on a GATE_SIZE^2 camera of the same view: the reference costs ~1 ms per
    # voxel piece in 50 digits, too slow for 64^2 images x 12 runs on the shared machine.
    for name in args.scenes.split(","):
        sp = paths[name]
        with open(sp) as f:
            gs = json.load(f)
        gs["camera"]["width"] = gs["camera"]["height"] = args.gate_size
        gp = os.path.join(vol_dir, name + "-gate.json")
        with open(gp, "w") as f:
            json.dump(gs, f, indent=1)
            f.write("\n")
        for mapper in mappers:
            mdir = os.path.join(out, name, mapper)
            r = results["scenes"][name]["mappers"].get(mapper, {})
            cand = os.path.join(mdir, "gate.npy")
            p = sh([sys.executable, me, "render", "--scene", gp, "--mapper", mapper, "--out", cand])
            if p.returncode != 0:
                r["gate_failed"] = "render exited with status %d" % p.returncode
                continue
            t0 = time.time()
            chk = sh([rayint, "check", gp, "--candidate-image", cand, "--abs-tol", str(args.abs_tol),
                      "--rel-tol", str(args.rel_tol), "--artifacts", os.path.join(mdir, "check"),
                      "--threads", "2", "-o", os.path.join(mdir, "diff.json"),
                      "--junit", os.path.join(mdir, "junit.xml")], capture_output=True, text=True)
            r["check_seconds"] = time.time() - t0
            r["check_exit"] = chk.returncode
            r["check_line"] = chk.stdout.strip().splitlines()[-1] if chk.stdout.strip() else chk.stderr.strip()
            results["scenes"][name]["mappers"][mapper] = r
            with open(os.path.join(out, "results.json"), "w") as f:
                json.dump(results, f, indent=1)
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    print("wrote", os.path.join(out, "results.json"), file=sys.stderr)


def translation_check(d, step=0.05):
    """The translation checks (self_check) plus renders of the constant scene, whose exact image is
    known in closed form: every mapper's float read-back at sample distance `step` within the
    first-order bound of a ray caster's step count (a chord of length L gets ceil-or-floor(L/d)
    samples: |dT| <= sigma d T, so |dI| <= sigma d max|kappa - B|), and the GPU digit decoding
    equal to the ordinary 8-bit read-back when rounded. Returns the list of failures."""
    paths = scenes(d)
    failures, _ = self_check(paths, verbose=True)
    with open(paths["constant"]) as f:
        sc = json.load(f)
    cf = closed_form_constant(sc, paths["constant"])
    sigma = sc["transfer"]["extinction"][0][1]
    kap = np.array([sc["transfer"]["emission"][c][0][1] for c in "rgb"])
    bg = np.array(sc["background"]["color"])
    bound = sigma * step * float(np.abs(kap - bg).max())
    hit = np.abs(cf - bg).max(axis=2) > 1e-3
    # away from the silhouette: FixedPoint's row bounds (ComputeRowBounds: x1 + 1.5 .. x1 - 1 on
    # the projected box edges) skip pixels up to 2 px inside it; those are counted, not bounded
    inside = hit.copy()
    for _ in range(2):
        inside[1:, :] &= inside[:-1, :].copy()
        inside[:-1, :] &= inside[1:, :].copy()
        inside[:, 1:] &= inside[:, :-1].copy()
        inside[:, :-1] &= inside[:, 1:].copy()
    for mapper in MAPPERS:
        rgb, info = render(paths["constant"], mapper, step)
        err = np.abs(rgb - cf).max(axis=2)
        worst = float(err[inside].max())
        dropped = int((hit & (np.abs(rgb - bg).max(axis=2) < 1e-9)).sum())
        line = ("translation %-18s constant volume, step %g: max |error| 2 px inside the silhouette %.3g "
                "(bound %.3g), median %.3g; silhouette max %.3g, %d of %d covered pixels left at the background") % (
            mapper, step, worst, bound, float(np.median(err[inside])), float(err[hit & ~inside].max()),
            dropped, int(hit.sum()))
        if "digit_decode_vs_8bit_max" in info:
            line += ", digits vs 8-bit %g" % info["digit_decode_vs_8bit_max"]
            if info["digit_decode_vs_8bit_max"] != 0.0:
                failures.append(mapper + ": decoded float image differs from the 8-bit read-back")
        print(line)
        if mapper == "fixedpoint-display":
            continue  # its own ray-cast image resampled by the display helper: reported, not bounded
        if not worst <= bound:
            failures.append("%s: constant volume error %.3g above the bound %.3g" % (mapper, worst, bound))
    print("translation:", "PASS" if not failures else "FAIL: " + "; ".join(failures))
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("self-check")
    s.add_argument("--dir", default=None, help="where to write the scenes (default: a temporary directory)")
    t = sub.add_parser("translation-check", help="self-check plus constant-volume renders (needs a display)")
    t.add_argument("--dir", default=None)
    t.add_argument("--step", type=float, default=0.05)
    r = sub.add_parser("render")
    r.add_argument("--scene", required=True)
    r.add_argument("--mapper", required=True, choices=MAPPERS)
    r.add_argument("--step", type=float, default=None, help="SampleDistance (world units); default: the mapper's")
    r.add_argument("--out", required=True, help=".npy (float64, H x W x 3, rows top-down)")
    r.add_argument("--info", default=None, help="write the render's settings as JSON here")
    u = sub.add_parser("run")
    u.add_argument("--rayint", required=True)
    u.add_argument("--out", required=True)
    u.add_argument("--scenes", default="constant,smooth,head")
    u.add_argument("--mappers", default=",".join(MAPPERS))
    u.add_argument("--abs-tol", type=float, default=1e-2)
    u.add_argument("--rel-tol", type=float, default=1e-2)
    u.add_argument("--error-maps", action="store_true", help="keep converge's per-step error maps (.npy)")
    u.add_argument("--gate-size", type=int, default=24, help="camera size of the rayint check gate")
    u.add_argument("--merge", action="store_true", help="keep the other scenes of an existing results.json")
    a = ap.parse_args()
    if a.cmd == "self-check":
        import tempfile
        d = a.dir or tempfile.mkdtemp(prefix="rayint-vtk-image-")
        failures, _ = self_check(scenes(d))
        sys.exit(1 if failures else 0)
    if a.cmd == "translation-check":
        import tempfile
        sys.exit(1 if translation_check(a.dir or tempfile.mkdtemp(prefix="rayint-vtk-image-"), a.step) else 0)
    if a.cmd == "render":
        rgb, info = render(a.scene, a.mapper, a.step)
        if not np.all(np.isfinite(rgb)):
            print(a.scene + ": the read-back holds NaN", file=sys.stderr)
            sys.exit(1)
        np.save(a.out, rgb)
        if a.info:
            with open(a.info, "w") as f:
                json.dump(info, f, indent=1)
        return
    run(a)


if __name__ == "__main__":
    main()
