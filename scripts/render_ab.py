#!/usr/bin/python3
"""Render speed of two rayint binaries, interleaved, beside VTK's projected tetrahedra (issue 33).

One run: for each round, each binary (which goes first alternates from round to round) renders
the 512 x 512 case (and the 16 x 16 case, the load alone) with each thread count, in turn; then,
optionally, VTK's vtkProjectedTetrahedraMapper
renders the same case (scripts/scaling.py --vtk-one under xvfb-run). Quoted: medians over the
rounds of
  render wall s   rayint's own summary line ("... rays in X s"), the render phase alone;
  render CPU s    user + system of the 512 x 512 process minus the median of the 16 x 16 one
                  (each from the process's rusage, to the microsecond);
  VTK frame       wall and CPU (process_time, llvmpipe's threads included) of a second Render().
The images of the two binaries are compared: max relative pixel difference (0 = identical).

With --png the timed renders write PNG files, as scripts/scaling.py's do (the render CPU then
includes the 8-bit encoding and the deflate); the images are compared from one more .npy render
of each binary after the rounds.

usage: render_ab.py --old OLD_RAYINT --new NEW_RAYINT --case CASE512.json --small CASE16.json
                    [--rounds 5] [--threads 1 2] [--vtk] [--png] [--json out.json]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

import numpy as np

import scaling  # scripts/scaling.py: timed()

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def timed(cmd):
    """(cpu_s, stdout, stderr): user + system from the process's own rusage, to the microsecond
    (scaling.timed; /usr/bin/time, used here until round 21, printed it in steps of 10 ms, 2% of
    the 105k render)."""
    try:
        cpu, _, out, err = scaling.timed(cmd)
    except scaling.RunFailed as e:
        raise SystemExit(str(e))
    return cpu, out, err


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--case", required=True)
    ap.add_argument("--small", required=True)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--vtk", action="store_true")
    ap.add_argument("--work", default="/tmp/rayint-render-ab")
    ap.add_argument("--json")
    ap.add_argument("--png", action="store_true", help="time renders to .png (as scaling.py), compare from .npy")
    a = ap.parse_args()
    ext = "png" if a.png else "npy"
    os.makedirs(a.work, exist_ok=True)
    bins = {"old": a.old, "new": a.new}
    res = {"load_start": loadavg(), "runs": {}}
    samples = {(b, t): {"wall": [], "cpu": []} for b in bins for t in a.threads}
    small = {b: [] for b in bins}
    vtk = []
    for r in range(a.rounds):
        # Which binary runs first alternates from round to round: with a fixed order, the same
        # binary as "old" and "new" measured 1.02x (1 thread) and 1.08x (2 threads) "faster" in
        # the second place (round 21, 15 rounds; reports/scaling/NOTES.md).
        order = list(bins.items()) if r % 2 == 0 else list(reversed(bins.items()))
        for t in a.threads:
            for b, exe in order:
                cpu, _, err = timed([exe, "render", a.case, "-o", os.path.join(a.work, "%s.%s" % (b, ext)), "--threads",
                                     str(t), "-q", "--stats", os.path.join(a.work, "%s.json" % b)])
                with open(os.path.join(a.work, "%s.json" % b)) as f:
                    wall = json.load(f)["cost"]["wall_seconds"]
                samples[(b, t)]["wall"].append(wall)
                samples[(b, t)]["cpu"].append(cpu)
        for b, exe in order:
            cpu, _, _ = timed([exe, "render", a.small, "-o", os.path.join(a.work, "small-%s.%s" % (b, ext)), "-q"])
            small[b].append(cpu)
        if a.vtk:
            p = subprocess.run(["xvfb-run", "-a", "/usr/bin/python3", os.path.join(ROOT, "scripts", "scaling.py"),
                                "--vtk-one", a.case, "projected_tetrahedra", "-"], capture_output=True, text=True)
            if p.returncode != 0:
                raise SystemExit("VTK failed: " + p.stderr[-800:])
            vtk.append(json.loads(p.stdout.strip().splitlines()[-1]))
        print("round %d done, load %s" % (r + 1, loadavg()), file=sys.stderr, flush=True)
    res["load_end"] = loadavg()
    if a.png:  # the images to compare
        for b, exe in bins.items():
            timed([exe, "render", a.case, "-o", os.path.join(a.work, "%s.npy" % b), "-q"])
    old_img = np.load(os.path.join(a.work, "old.npy"))
    new_img = np.load(os.path.join(a.work, "new.npy"))
    den = np.abs(old_img)
    diff = np.abs(new_img - old_img)
    rel = np.where(den > 0, diff / np.where(den > 0, den, 1.0), np.where(diff > 0, np.inf, 0.0))
    res["image_max_rel_diff"] = float(rel.max())
    res["image_identical"] = bool(np.array_equal(old_img, new_img))
    small_med = {b: statistics.median(v) for b, v in small.items()}
    res["small_cpu_median"] = small_med
    rows = []
    for t in a.threads:
        row = {"threads": t}
        for b in bins:
            s = samples[(b, t)]
            row[b + "_wall"] = statistics.median(s["wall"])
            row[b + "_cpu"] = statistics.median(s["cpu"]) - small_med[b]
            row[b + "_samples"] = s
        row["speedup_wall"] = row["old_wall"] / row["new_wall"]
        row["speedup_cpu"] = row["old_cpu"] / row["new_cpu"]
        rows.append(row)
    res["rows"] = rows
    if vtk:
        res["vtk_frame_wall_median"] = statistics.median(v["frame_s"] for v in vtk)
        res["vtk_frame_cpu_median"] = statistics.median(v["frame_cpu_s"] for v in vtk)
        res["vtk_samples"] = vtk
    print("| threads | old wall s | new wall s | wall speed-up | old CPU s | new CPU s | CPU speed-up |"
          + (" VTK PT frame wall / CPU s | VTK/new wall | VTK/new CPU |" if vtk else ""))
    print("|---|---|---|---|---|---|---|" + ("---|---|---|" if vtk else ""))
    for row in rows:
        line = "| %d | %.3f | %.3f | %.2f | %.3f | %.3f | %.2f |" % (
            row["threads"], row["old_wall"], row["new_wall"], row["speedup_wall"], row["old_cpu"], row["new_cpu"],
            row["speedup_cpu"])
        if vtk:
            line += " %.3f / %.3f | %.2f | %.2f |" % (
                res["vtk_frame_wall_median"], res["vtk_frame_cpu_median"],
                res["vtk_frame_wall_median"] / row["new_wall"], res["vtk_frame_cpu_median"] / row["new_cpu"])
        print(line)
    print("images: identical %s, max relative pixel difference %.3g; load average start %s, end %s" % (
        res["image_identical"], res["image_max_rel_diff"], res["load_start"], res["load_end"]))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
