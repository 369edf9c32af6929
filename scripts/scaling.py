#!/usr/bin/python3
"""Measures how rayint scales with the size of a tetrahedral mesh (issue 33) and renders the same
meshes with VTK's unstructured-grid volume mappers: writes reports/scaling/results.json.

Run it through scripts/scaling.sh (it generates the meshes, gives VTK an X display with xvfb-run
and draws the report). Meshes: `rayint generate-mesh ball --n N` (48 N^3 tets: N = 6, 13, 28, 60
give 10k, 105k, 1.05M, 10.4M), written as binary .vtk and, by scripts/big_meshes.py, as .vtu
(VTK's writer, appended raw) and .msh (meshio, MSH 4.1 binary), kept in --work (never the repo).

Every figure is a median over --repeats runs; runs of the binaries compared (--before, the
current build) are interleaved, so a change of the machine's load hits both alike. Times:
  cpu_s   user + system CPU seconds of the whole process (its rusage), the load measures;
  wall_s  elapsed seconds of a render phase (rayint's own summary; VTK: around Render());
  render CPU: rayint, CPU of the 512 x 512 run minus the 16 x 16 one; VTK, process_time() around
          Render() (every thread: llvmpipe's rasteriser threads too), the fairer measure when
          the wall clock depends on what the other engineers run.
The machine is shared (2 cores, ~6 engineers building): wall-clock times are noisy, ratios
measured side by side are what the report quotes; the load average at the start and the end
is recorded.

Phases of rayint's load, per file (one process each):
  read    `rayint mesh info FILE`: parse + assemble the TetMesh (+ orientation counts);
  check   `rayint mesh info FILE --quick-check` minus read: the overlap check a case runs on load;
  load    `rayint render` of the case at 16 x 16, minus nothing: read + repair + check + the
          traversal build + 256 rays (negligible): the end-to-end load, per tet;
  build   load minus read and check (repair, the traversal's faces, cell records, Embree BVH).
Peak memory: peak RSS (the process's rusage) of `rayint render` at 512 x 512, per tet, and the
fixed part (the 16 x 16 render of the 10k mesh) subtracted for the per-tet slope.

usage: scaling.py --rayint build/rayint [--before OLD_RAYINT] --work /tmp/rayint-scaling
                  --sizes 6 13 28 [--vtk-sizes 6 13 28] [--repeats 3] --out reports/scaling
       scaling.py --vtk-one CASE.json MAPPER INTEGRATOR   (one VTK render, JSON on stdout)
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TF = {
    "density": [[0.0, 0.2], [0.3, 2.0], [0.6, 0.5], [1.0, 4.0]],
    "color": {"r": [[0.0, 1.0], [0.5, 0.2], [1.0, 1.5]],
              "g": [[0.0, 0.1], [0.5, 1.0], [1.0, 0.3]],
              "b": [[0.0, 0.4], [1.0, 0.9]]},
}
CAMERA = {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40}
# VTK's unstructured-grid volume mappers (VTK 9.1): the projected tetrahedra mapper (OpenGL, here
# Mesa llvmpipe on the CPU), the ray caster with each of its integrators, and the ZSweep mapper.
VTK_MAPPERS = [("projected_tetrahedra", ""), ("raycast", "homogeneous"), ("raycast", "linear"),
               ("raycast", "partial_preint"), ("raycast", "preint"), ("zsweep", "")]


def loadavg():
    with open("/proc/loadavg") as f:
        return [float(x) for x in f.read().split()[:3]]


class RunFailed(Exception):
    pass


def timed(cmd, env=None):
    """(cpu_s, peak_rss_kb, stdout, stderr) of one process, from its own rusage (os.wait4): user +
    system to the microsecond (Linux accounts run time in nanoseconds; /usr/bin/time, used until
    round 9, printed it in steps of 10 ms, 0.1 us per tet on the 105k mesh) and its peak RSS."""
    with tempfile.TemporaryFile("w+") as fo, tempfile.TemporaryFile("w+") as fe:
        p = subprocess.Popen(cmd, stdout=fo, stderr=fe, text=True, env=env)
        _, status, ru = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        fo.seek(0)
        fe.seek(0)
        out, err = fo.read(), fe.read()
    if p.returncode != 0:
        how = "killed by signal %d" % -p.returncode if p.returncode < 0 else "exit %d" % p.returncode
        raise RunFailed("failed (%s): %s\n%s" % (how, " ".join(cmd), err[-600:]))
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss, out, err


def case(path, mesh_file, size):
    c = {"name": "scaling", "transfer_function": TF, "mesh_file": mesh_file,
         "background": [0.05, 0.05, 0.1], "camera": dict(CAMERA, width=size, height=size)}
    with open(path, "w") as f:
        json.dump(c, f, indent=1)
    return path


def med(xs):
    return statistics.median(xs) if xs else None


def rayint_runs(binaries, work, n, fmt, repeats):
    """Load phases and render of one mesh file for each binary, interleaved."""
    mesh = os.path.join(work, "ball-%d.%s" % (n, fmt))
    small = case(os.path.join(work, "load-%d-%s.json" % (n, fmt)), mesh, 16)
    big = case(os.path.join(work, "render-%d-%s.json" % (n, fmt)), mesh, 512)
    out = {name: {"read": [], "check": [], "load": [], "render_wall": [], "render_rss_kb": [],
                  "load_rss_kb": [], "rays_per_s": [], "render_cpu": []} for name in binaries}
    for _ in range(repeats):
        for name, exe in binaries.items():
            r = out[name]
            cpu, _, _, _ = timed([exe, "mesh", "info", mesh, "--format", "json"])
            r["read"].append(cpu)
            cpu_c, _, _, _ = timed([exe, "mesh", "info", mesh, "--quick-check", "--format", "json"])
            r["check"].append(max(0.0, cpu_c - cpu))
            cpu_l, rss_l, _, _ = timed([exe, "render", small, "-o", os.path.join(work, "o.png"), "-q"])
            r["load"].append(cpu_l)
            r["load_rss_kb"].append(rss_l)
            if fmt == "vtk":  # the render is the same whatever the format
                cpu_r, rss, _, err = timed([exe, "render", big, "-o", os.path.join(work, "o-%s.png" % name),
                                            "--threads", "2"])
                r["render_cpu"].append(max(0.0, cpu_r - cpu_l))  # the 512 x 512 run minus the 16 x 16 one
                m = re.search(r"(\d+) rays in ([\d.e+-]+) s on (\d+) threads", err)
                if not m:
                    raise SystemExit("no render summary from " + exe + ":\n" + err[-1000:])
                r["render_wall"].append(float(m.group(2)))
                r["rays_per_s"].append(int(m.group(1)) / float(m.group(2)))
                r["render_rss_kb"].append(rss)
    res = {}
    for name, r in out.items():
        res[name] = {k: med(v) for k, v in r.items()}
        res[name]["build"] = max(0.0, res[name]["load"] - res[name]["read"] - res[name]["check"])
        res[name]["samples"] = r
    return res


def vtk_one(case_path, mapper, integrator):
    """One VTK render of a case at its camera, timed: the first frame (the mapper's setup, e.g.
    the ray caster's face lists, plus a frame) and the second (a frame alone)."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import vtk_render as vr
    import vtk
    with open(case_path) as f:
        c = json.load(f)
    cam = c["camera"]
    w, h = cam["width"], cam["height"]
    t0 = time.perf_counter()
    grid = vr.vtk_grid(c, case_path)
    t_read = time.perf_counter() - t0
    opacity, colour, unit = vr.vtk_transfer(c)
    win, ren, _ = vr.offscreen_volume(vr.tet_mapper(mapper, integrator), grid,
                                      vr.volume_property(opacity, colour, unit), w, h)
    ren.SetBackground(*c.get("background", [0.0, 0.0, 0.0]))
    ren.SetActiveCamera(vr.make_vtk_camera(cam, vr.vtk_camera_settings(cam, mapper, "nominal")))
    ren.ResetCameraClippingRange()
    arr = vtk.vtkUnsignedCharArray()
    t0, c0 = time.perf_counter(), time.process_time()
    win.Render()
    win.GetRGBACharPixelData(0, 0, w - 1, h - 1, 0, arr)  # waits for the frame to finish
    t_first, c_first = time.perf_counter() - t0, time.process_time() - c0
    # A new frame: the camera moves by a hair, so nothing cached for the last view is reused.
    ren.GetActiveCamera().Azimuth(1e-6)
    t0, c0 = time.perf_counter(), time.process_time()
    win.Render()
    win.GetRGBACharPixelData(0, 0, w - 1, h - 1, 0, arr)
    t_second, c_second = time.perf_counter() - t0, time.process_time() - c0
    # process_time: CPU of every thread of the process (llvmpipe's rasteriser threads too).
    print(json.dumps({"read_s": t_read, "first_frame_s": t_first, "frame_s": t_second,
                      "first_frame_cpu_s": c_first, "frame_cpu_s": c_second, "cells": grid.GetNumberOfCells()}))


def vtk_runs(work, n, repeats, skip):
    mesh = os.path.join(work, "ball-%d.vtk" % n)
    path = case(os.path.join(work, "render-%d-vtk.json" % n), mesh, 512)
    res = {}
    for mapper, integ in VTK_MAPPERS:
        key = mapper + ("-" + integ if integ else "")
        if key in skip:
            res[key] = {"skipped": skip[key]}
            continue
        runs = []
        try:
            for _ in range(repeats):
                _, rss, out, _ = timed(["/usr/bin/python3", os.path.abspath(__file__), "--vtk-one", path, mapper,
                                        integ or "-"])
                d = json.loads(out.strip().splitlines()[-1])
                d["rss_kb"] = rss
                runs.append(d)
        except RunFailed as e:  # shown as failed in the report, never as a time
            res[key] = {"failed": str(e).splitlines()[0][:300] + " " + " ".join(str(e).split())[-200:]}
            skip[key] = "failed at a smaller size"
            continue
        res[key] = {k: med([r[k] for r in runs])
                    for k in ("read_s", "first_frame_s", "frame_s", "first_frame_cpu_s", "frame_cpu_s", "rss_kb")}
        res[key]["samples"] = runs
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rayint", default=os.path.join(ROOT, "build", "rayint"))
    ap.add_argument("--before", help="an older rayint binary measured side by side")
    ap.add_argument("--work", default="/tmp/rayint-scaling")
    ap.add_argument("--sizes", type=int, nargs="+", default=[6, 13, 28])
    ap.add_argument("--vtk-sizes", type=int, nargs="*", default=None)
    ap.add_argument("--formats", nargs="*", default=["vtk", "vtu", "msh"],
                    help="the files rayint loads (none: only the VTK mappers)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--vtk-budget", type=float, default=240.0,
                    help="skip a VTK mapper at the next size when its frame would exceed this (s), "
                         "extrapolated linearly in the tets")
    ap.add_argument("--out", default=os.path.join(ROOT, "reports", "scaling"))
    ap.add_argument("--vtk-one", nargs=3)
    ap.add_argument("--vtk-mappers", nargs="*", default=None,
                    help="only these VTK mappers (e.g. projected_tetrahedra raycast-homogeneous)")
    a = ap.parse_args()
    if a.vtk_one:
        vtk_one(a.vtk_one[0], a.vtk_one[1], "" if a.vtk_one[2] == "-" else a.vtk_one[2])
        return
    binaries = {"after": os.path.abspath(a.rayint)}
    if a.before:
        binaries = {"before": os.path.abspath(a.before), "after": os.path.abspath(a.rayint)}
    vtk_sizes = a.sizes if a.vtk_sizes is None else a.vtk_sizes
    os.makedirs(a.out, exist_ok=True)
    result = {"load_average_start": loadavg(), "nproc": os.cpu_count(), "binaries": binaries,
              "repeats": a.repeats, "started": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
              "sizes": []}
    skip = {}
    if a.vtk_mappers is not None:
        for mapper, integ in VTK_MAPPERS:
            key = mapper + ("-" + integ if integ else "")
            if key not in a.vtk_mappers:
                skip[key] = "not asked for (--vtk-mappers)"
    for n in a.sizes:
        tets = 48 * n ** 3
        row = {"n": n, "tets": tets, "formats": {}}
        for fmt in a.formats:
            print("ball-%d.%s: rayint ..." % (n, fmt), file=sys.stderr, flush=True)
            row["formats"][fmt] = rayint_runs(binaries, a.work, n, fmt, a.repeats)
        if n in vtk_sizes:
            print("ball-%d: VTK mappers ..." % n, file=sys.stderr, flush=True)
            row["vtk"] = vtk_runs(a.work, n, a.repeats if tets < 200_000 else (2 if tets < 2_000_000 else 1), skip)
            nxt = [m for m in vtk_sizes if m > n]
            for key, v in row["vtk"].items():
                if "frame_s" in v and nxt:
                    guess = v["first_frame_s"] * 48 * nxt[0] ** 3 / tets
                    if guess > a.vtk_budget:
                        skip[key] = "first frame estimated at %.0f s at the next size (%.0f s here)" % (
                            guess, v["first_frame_s"])
        result["sizes"].append(row)
        with open(os.path.join(a.out, "results.json"), "w") as f:  # partial results survive an abort
            json.dump(result, f, indent=1)
    result["load_average_end"] = loadavg()
    result["finished"] = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())
    with open(os.path.join(a.out, "results.json"), "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
