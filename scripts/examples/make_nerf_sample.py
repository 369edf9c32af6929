#!/usr/bin/python3
"""Writes scripts/examples/nerf_sample.npz: a small, deterministic stand-in for the samples a NeRF
renderer takes along its rays (what nerf_quadrature_error.py reads), so the example and its test
run without a trained model.

Layout, as NeRF 2020's render_rays has it: 16 rays, 64 stratified samples each between near = 2 and
far = 6 (the Blender scenes' bounds), t increasing from the eye; a density with one soft shell per
ray (a Gaussian in t of peak 5..200 and width 0.02..0.3, the kind of surface a trained NeRF puts
its density in) over a haze of 0.05, and a colour that varies smoothly along the ray, in [0, 1].

usage: make_nerf_sample.py [OUT.npz]      (default: nerf_sample.npz beside this script)
"""
import os
import sys

import numpy as np


def main(argv):
    out = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                      "nerf_sample.npz")
    rng = np.random.default_rng(20230919)
    rays, n, near, far = 16, 64, 2.0, 6.0
    edges = np.linspace(near, far, n + 1)
    t = edges[:-1] + (edges[1:] - edges[:-1]) * rng.random((rays, n))  # stratified, increasing
    t[:, 0], t[:, -1] = near, far  # the ray's ends are samples, as with NeRF's linspace
    depth = rng.uniform(3.0, 5.0, (rays, 1))
    width = np.exp(rng.uniform(np.log(0.02), np.log(0.3), (rays, 1)))
    peak = np.exp(rng.uniform(np.log(5.0), np.log(200.0), (rays, 1)))
    sigma = 0.05 + peak * np.exp(-((t - depth) / width) ** 2)
    phase = rng.uniform(0.0, 2.0 * np.pi, (rays, 1, 3))
    rgb = 0.5 + 0.45 * np.sin(1.7 * t[..., None] + phase)
    np.savez(out, t=t, sigma=sigma, rgb=rgb, background=np.array([1.0, 1.0, 1.0]))
    print(f"wrote {out}: {rays} rays x {n} samples")


if __name__ == "__main__":
    main(sys.argv)
