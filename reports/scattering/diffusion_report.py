#!/usr/bin/python3
"""Diffusion (P1) on voxel grids against the Monte Carlo on the same grid: the scene effect
`multiple_scattering` (orders >= 2) rendered alone by `rayint render`, method diffusion:grid=G,
against monte_carlo:spp=N with two seeds (their difference measures the reference's own noise),
with discrete_ordinates beside it. Scenes: Max's cloud (cases/scenes/cloud-multiple-scattering.json
with only the multiple_scattering effect, 64 x 64 pixels) and a homogeneous cube in four regimes
(optical size 1 and 10, albedo 0.5 and 0.99).

Writes reports/scattering/diffusion.json and prints the markdown table (pasted into diffusion.md).

Usage: /usr/bin/python3 reports/scattering/diffusion_report.py [BUILD_DIR] [SPP]   (build/, 2048)
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
SPP = int(sys.argv[2]) if len(sys.argv) > 2 else 2048
RAYINT = os.path.join(BUILD, "rayint")
OUT = os.path.join(ROOT, "reports", "scattering")
PIXELS = 64


def cube_scene(sigma, albedo):
    return {
        "name": f"cube-tau{sigma:g}-albedo{albedo:g}",
        "medium": {"type": "homogeneous", "shape": "box", "density": 1, "lower": [0, 0, 0], "upper": [1, 1, 1]},
        "transfer": {"extinction": [[0, 0], [1, sigma]], "albedo": [[0, albedo]]},
        "lights": [{"type": "directional", "direction": [0.3, 0.2, -1], "intensity": 1}],
        "phase": {"type": "isotropic"},
        "camera": {"position": [0.5, 2.5, 3.5], "look_at": [0.5, 0.5, 0.5], "fov_deg": 30,
                   "width": PIXELS, "height": PIXELS},
        "background": {"color": [0, 0, 0]},
        "effects": ["multiple_scattering"],
    }


def cloud_scene():
    with open(os.path.join(ROOT, "cases", "scenes", "cloud-multiple-scattering.json")) as f:
        s = json.load(f)
    s["camera"]["width"] = s["camera"]["height"] = PIXELS
    s["effects"] = ["multiple_scattering"]
    s["methods"] = {}
    return s


def render(scene_path, method, tmp):
    out = os.path.join(tmp, "img.npy")
    stats = os.path.join(tmp, "stats.json")
    t0 = time.time()
    subprocess.run([RAYINT, "render", scene_path, "-o", out, "--method", "multiple_scattering=" + method,
                    "--stats", stats, "-q"], check=True)
    wall = time.time() - t0
    img = np.load(out)[..., 0] if np.load(out).ndim == 3 else np.load(out)
    with open(stats) as f:
        st = json.load(f)
    ms = [e for e in st["effects"] if e["effect"] == "multiple_scattering"][0]
    return img.astype(float), {"wall_seconds": wall, "setup_seconds": ms["setup_seconds"], "seconds": ms["seconds"]}


def errors(img, ref):
    m = ref.mean()
    return {"brightness_rel": float((img.mean() - m) / m), "mean_abs_rel": float(np.abs(img - ref).mean() / m),
            "max_abs_rel_to_peak": float(np.abs(img - ref).max() / ref.max())}


def main():
    scenes = [("cloud (Max 1995, extinction 12, albedo 0.95)", cloud_scene())]
    for sigma in (10, 1):
        for albedo in (0.99, 0.5):
            scenes.append((f"cube, optical size {sigma}, albedo {albedo}", cube_scene(sigma, albedo)))
    methods = ["diffusion:grid=16", "diffusion:grid=32", "diffusion:grid=48", "discrete_ordinates:grid=32:bins=3"]
    result = {"spp": SPP, "pixels": PIXELS, "scenes": []}
    with tempfile.TemporaryDirectory() as tmp:
        for label, scene in scenes:
            path = os.path.join(tmp, "scene.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            ref1, c1 = render(path, f"monte_carlo:spp={SPP}:seed=1", tmp)
            ref2, c2 = render(path, f"monte_carlo:spp={SPP}:seed=2", tmp)
            ref = 0.5 * (ref1 + ref2)
            # The noise of the mean of the two: half the seeds' difference has its variance.
            noise = errors(0.5 * (ref1 - ref2) + ref, ref)
            row = {"scene": label, "reference_spp": 2 * SPP, "reference_mean": float(ref.mean()),
                   "reference_noise": noise, "reference_seconds": c1["wall_seconds"] + c2["wall_seconds"],
                   "methods": []}
            for m in methods:
                img, cost = render(path, m, tmp)
                row["methods"].append({"method": m, **errors(img, ref), **cost})
            result["scenes"].append(row)
            print(label, json.dumps(row["methods"], indent=0)[:400], file=sys.stderr)
    with open(os.path.join(OUT, "diffusion.json"), "w") as f:
        json.dump(result, f, indent=1)
    print("| scene | method | brightness error | mean abs pixel error / mean | setup s |")
    print("|---|---|---:|---:|---:|")
    for row in result["scenes"]:
        n = row["reference_noise"]
        print(f"| {row['scene']} | Monte Carlo noise ({row['reference_spp']} spp) | {n['brightness_rel']:+.1e} | "
              f"{n['mean_abs_rel']:.1e} | |")
        for m in row["methods"]:
            print(f"| | {m['method']} | {m['brightness_rel']:+.3f} | {m['mean_abs_rel']:.3f} | {m['setup_seconds']:.2f} |")


if __name__ == "__main__":
    main()
