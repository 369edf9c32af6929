#!/usr/bin/python3
"""How far is your NeRF quadrature from the exact integral, on your own samples?

A NeRF renderer samples density sigma and colour c at positions t along each ray and sums
C = sum_i T_i (1 - exp(-sigma_i delta_i)) c_i (Mildenhall et al. 2020, Eq. 3). Between the
samples it knows nothing, so the natural "truth" for its samples is the emission-absorption
integral (Max 1995, Eq. 1) of the piecewise-linear interpolant of sigma and c through them. rayint
computes that integral exactly (Williams & Max 1992, Sec. 3.3; rayint.exact_pieces, ~1e-15
relative against a 50-digit reference), so the difference is the error of the quadrature alone.

Input: an .npz with
    t      (rays, N) or (N,)  sample positions along each ray, increasing away from the eye
    sigma  (rays, N)          density at the samples (after the activation, >= 0)
    rgb    (rays, N, 3)       colour at the samples
    background (3,), optional  colour behind the ray's last sample (default black)
e.g. from NeRF 2020's render_rays: t = z_vals, sigma = relu(raw[..., 3]), rgb = sigmoid(raw[..., :3]);
ray directions of non-unit length: multiply t by |d| first (run_nerf.py does so for its deltas).

Compared over [t_0, t_{N-1}], each plus T * background:
    exact         integral of the piecewise-linear interpolant (rayint.exact_pieces per interval)
    nerf          NeRF 2020's sum, delta_i = t_{i+1} - t_i, sample at the interval's eye-side end
                  (the last sample's interval is empty here; see nerf 1e10)
    nerf bins     nerfstudio-style bins centred on the samples: delta_i = (t_{i+1} - t_{i-1}) / 2,
                  half bins at both ends
    pl_nerf       Uy et al. 2023: linear density between samples, exact transmittance, colour
                  (c_i + c_{i+1}) / 2
    pl_nerf near  the same with the eye-side colour c_i (PL-NeRF's color_mode "left")
    nerf 1e10     NeRF 2020 exactly as published: the last delta is 1e10, so the last sample is
                  opaque wherever its density is > 0 and replaces the background (its error
                  includes that wall)

usage: nerf_quadrature_error.py SAMPLES.npz [--json] [--background R,G,B]
Run with /usr/bin/python3 and PYTHONPATH=build/python (the rayint module).
"""
import argparse
import json
import sys

import numpy as np

import rayint


def load(path, background_arg):
    with np.load(path) as f:
        for key in ("t", "sigma", "rgb"):
            if key not in f:
                raise SystemExit(f"{path}: missing array '{key}' (needs t, sigma, rgb)")
        sigma = np.atleast_2d(np.asarray(f["sigma"], dtype=np.float64))
        rgb = np.asarray(f["rgb"], dtype=np.float64)
        rgb = rgb.reshape(sigma.shape + (3,)) if rgb.ndim == 2 and sigma.shape[0] == 1 else rgb
        t = np.broadcast_to(np.asarray(f["t"], dtype=np.float64), sigma.shape)
        background = np.asarray(f["background"], dtype=np.float64) if "background" in f else np.zeros(3)
    if background_arg:
        background = np.array([float(x) for x in background_arg.split(",")], dtype=np.float64)
    if rgb.shape != sigma.shape + (3,):
        raise SystemExit(f"{path}: rgb must have shape {sigma.shape + (3,)}, got {rgb.shape}")
    if sigma.shape[-1] < 2:
        raise SystemExit(f"{path}: need at least 2 samples per ray")
    if not np.all(np.diff(t, axis=-1) >= 0):
        raise SystemExit(f"{path}: t must increase along each ray (away from the eye)")
    if background.shape != (3,):
        raise SystemExit(f"{path}: background must have 3 values")
    return t, sigma, rgb, background


def exact_interpolant(t, sigma, rgb, background):
    """Exact integral over [t_0, t_{N-1}] of the piecewise-linear sigma and rgb, front to back."""
    delta = np.diff(t, axis=-1)[..., None]                        # (rays, N-1, 1)
    emission, trans = rayint.exact_pieces(sigma[..., :-1, None], sigma[..., 1:, None],
                                          rgb[..., :-1, :], rgb[..., 1:, :], delta)
    # T before each interval: exclusive product from the eye.
    before = np.cumprod(np.concatenate([np.ones_like(trans[..., :1, :]), trans[..., :-1, :]],
                                       axis=-2), axis=-2)
    total_t = before[..., -1, :] * trans[..., -1, :]
    return (before * emission).sum(axis=-2) + total_t * background, total_t


def quadratures(t, sigma, rgb, background):
    out = {}
    out["nerf"] = rayint.nerf_composite(sigma, rgb, rayint.nerf_deltas(t, last="none"),
                                        background=background)[0]
    mids = 0.5 * (t[..., 1:] + t[..., :-1])
    lo = np.concatenate([t[..., :1], mids], axis=-1)
    hi = np.concatenate([mids, t[..., -1:]], axis=-1)
    out["nerf bins"] = rayint.nerf_composite(sigma, rgb, hi - lo, background=background)[0]
    out["pl_nerf"] = rayint.pl_nerf_composite(sigma, rgb, t, color="mid", background=background)[0]
    out["pl_nerf near"] = rayint.pl_nerf_composite(sigma, rgb, t, color="near",
                                                   background=background)[0]
    out["nerf 1e10"] = rayint.nerf_composite(sigma, rgb, rayint.nerf_deltas(t, last="1e10"),
                                             background=background)[0]
    return out


def summarise(values, exact):
    err = np.abs(values - exact)
    rel = np.where(exact != 0, err / np.abs(np.where(exact != 0, exact, 1.0)),
                   np.where(err == 0, 0.0, np.inf))
    return {"max_abs_error": float(err.max()), "median_abs_error": float(np.median(err)),
            "max_rel_error": float(rel.max()), "median_rel_error": float(np.median(rel)),
            "max_error_8bit_levels": float(err.max() * 255.0)}


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("samples", help=".npz with t, sigma, rgb (and optionally background)")
    ap.add_argument("--json", action="store_true", help="print JSON (per-ray values included)")
    ap.add_argument("--background", help="R,G,B behind the last sample (overrides the file's)")
    args = ap.parse_args(argv[1:])
    t, sigma, rgb, background = load(args.samples, args.background)
    exact, transmittance = exact_interpolant(t, sigma, rgb, background)
    quads = quadratures(t, sigma, rgb, background)
    report = {"samples": args.samples, "rays": int(sigma.shape[0]), "samples_per_ray": int(sigma.shape[1]),
              "background": background.tolist(),
              "errors": {name: summarise(v, exact) for name, v in quads.items()}}
    if args.json:
        report["exact"] = exact.tolist()
        report["transmittance"] = transmittance.tolist()
        report["values"] = {name: v.tolist() for name, v in quads.items()}
        json.dump(report, sys.stdout, indent=1)
        print()
        return 0
    print(f"{args.samples}: {report['rays']} rays x {report['samples_per_ray']} samples, "
          f"background {background.tolist()}")
    print("error against the exact integral of the piecewise-linear interpolant (r, g, b):")
    print(f"{'quadrature':<14} {'max abs':>10} {'median abs':>11} {'max rel':>10} {'8-bit levels':>13}")
    for name, e in report["errors"].items():
        print(f"{name:<14} {e['max_abs_error']:10.3g} {e['median_abs_error']:11.3g} "
              f"{e['max_rel_error']:10.3g} {e['max_error_8bit_levels']:13.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
