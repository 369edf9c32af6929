"""rayint from Python: the exact emission-absorption ray integral (Williams & Max 1992) on NumPy
arrays, the 50-digit reference, `rayint eval` and `rayint check` as functions, and the NeRF
quadratures (nerf, pl_nerf) on explicit samples.

Every function calls the same C++ code as the `rayint` CLI (src/python/module.cpp), so the
numbers are the CLI's bit for bit. Bad input raises rayint.InputError (a ValueError) carrying the
CLI's one-line message `<file>: <field>: <what>`; so does a method spec that is not valid (unknown
method or parameter, a value of the wrong type or out of range: "riemann:n=0: n must be an
integer >= 1"), before anything runs. A method that fails at run time on a ray is reported as
failed, never as a number: evaluate() gives null errors, "failed": true and the "failure" text
for that ray, and a "failed" count per method in each case's "summary".

Conventions (model/ray.hpp): a piece or segment has two ends, `exit` (the eye side) and `far`
(where light enters); rays run from the far end toward the eye.
"""
import json
import os

import numpy as np

from . import _rayint
from ._rayint import InputError

__all__ = ["InputError", "exact_pieces", "exact_grad", "exact_ray_grad", "evaluate", "reference", "check", "integrate",
           "method_names", "methods", "nerf_composite", "nerf_deltas", "pl_nerf_composite"]


def _document(obj, what):
    """A case/candidate as a path (str or os.PathLike) or a dict (JSON-serialisable)."""
    if isinstance(obj, (str, os.PathLike)):
        return _rayint._Document(True, os.fspath(obj), os.fspath(obj))
    if isinstance(obj, dict):
        return _rayint._Document(False, json.dumps(obj, allow_nan=False), "<" + what + " dict>")
    raise TypeError(f"{what} must be a path or a dict, got {type(obj).__name__}")


def _methods_csv(methods):
    if methods is None:
        return ""
    if isinstance(methods, str):
        return methods
    return ",".join(methods)


def exact_pieces(rho_exit, rho_far, kappa_exit, kappa_far, length):
    """Exact emission and transmittance of linear pieces (one channel each).

    On a piece of length L the density rho and the colour kappa vary linearly from their values
    at the exit (eye) end to those at the far end. Returns (emission, transmittance), float64
    arrays of the broadcast shape of the inputs:
        emission      = int_0^L kappa(s) rho(s) exp(-int_0^s rho) ds   (s from the exit end)
        transmittance = exp(-L (rho_exit + rho_far) / 2)
    The same C++ function as the `exact` method (integrators/exact_batch.hpp -> exact_piece),
    with the GIL released. rho and length must be finite and >= 0, kappa finite.
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64)
                                   for a in (rho_exit, rho_far, kappa_exit, kappa_far, length)))
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a).reshape(-1) for a in arrays]
    emission, transmittance = _rayint._exact_pieces(*flat)
    return emission.reshape(shape), transmittance.reshape(shape)


def exact_grad(rho_exit, rho_far, kappa_exit, kappa_far, length):
    """exact_pieces and its exact derivatives (issue 28; docs/gradients.md).

    Same inputs and broadcasting as exact_pieces. Returns a dict of float64 arrays of the
    broadcast shape: "emission", "transmittance", and "d_emission" / "d_transmittance", each a
    dict over the inputs ("rho_exit", "rho_far", "kappa_exit", "kappa_far", "length"; the
    transmittance does not depend on kappa, so its two kappa entries are zeros). The C++
    exact_piece_grad (integrators/exact_grad.hpp), GIL released; accurate to ~1e-15 of the
    largest derivative (tests/test_grad.cpp).
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64)
                                   for a in (rho_exit, rho_far, kappa_exit, kappa_far, length)))
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a).reshape(-1) for a in arrays]
    out = [a.reshape(shape) for a in _rayint._exact_grad(*flat)]
    zeros = np.zeros(shape)
    return {
        "emission": out[0],
        "transmittance": out[1],
        "d_emission": {"rho_exit": out[2], "rho_far": out[3], "kappa_exit": out[4],
                       "kappa_far": out[5], "length": out[6]},
        "d_transmittance": {"rho_exit": out[7], "rho_far": out[8], "kappa_exit": zeros,
                            "kappa_far": zeros.copy(), "length": out[9]},
    }


def _six_functions(density, color):
    """density, color: one (positions, values) pair for all channels, or a list of three."""
    out = []
    for name, f in (("density", density), ("color", color)):
        if len(f) == 2:  # one (positions, values) pair for r, g and b
            f = [f, f, f]
        if len(f) != 3:
            raise ValueError(f"exact_ray_grad: {name}: one (positions, values) pair or three")
        for p, v in f:
            out.append((np.ascontiguousarray(p, dtype=np.float64).reshape(-1),
                        np.ascontiguousarray(v, dtype=np.float64).reshape(-1)))
    return out


def exact_ray_grad(length, scalar_far, scalar_exit, background, density, color):
    """One ray's exact intensity and its exact gradient (issue 28; docs/gradients.md).

    Segments far -> near as 1-D arrays (length, scalar_far, scalar_exit), background (3,), and the
    transfer functions: density and color each one (positions, values) pair for all channels or a
    list of three (r, g, b). Returns a dict in `rayint grad`'s layout: "intensity" (3,),
    "background" (3,) = dI_c/dB_c, "length", "scalar_far", "scalar_exit" (n, 3) = dI_c/d(segment
    input), "density" and "color": lists of three (k, 2) arrays [dI_c/d position, dI_c/d value]
    for the nodes of channel c's function (a shared function: add the three for a loss of all
    channels). The C++ exact_ray_gradient (integrators/exact_grad.hpp), GIL released.
    """
    arrays = [np.ascontiguousarray(a, dtype=np.float64).reshape(-1) for a in (length, scalar_far, scalar_exit)]
    bg = np.ascontiguousarray(background, dtype=np.float64).reshape(-1)
    intensity, d_bg, d_len, d_far, d_exit, nodes = _rayint._exact_ray_grad(*arrays, bg, _six_functions(density, color))
    return {"intensity": intensity, "background": d_bg, "length": d_len, "scalar_far": d_far,
            "scalar_exit": d_exit, "density": list(nodes[:3]), "color": list(nodes[3:])}


def _split(cells):
    """cells="own" (default) or "split", as the CLI's `--cells`."""
    if cells not in ("own", "split"):
        raise ValueError(f"cells must be 'own' or 'split', got {cells!r}")
    return cells == "split"


def evaluate(case, methods=None, timing=True, threads=0, cells="own"):
    """`rayint eval` on one case (a path or a dict), a folder of cases, or a list of them.

    methods: a list of spec strings ("exact", "riemann:n=64", "nerf:n=32", ...) or one
    comma-separated string; None runs rayint eval's default (exact, paper). Returns the same
    structure as `rayint eval --format json` (timing=False is `--no-timing`): a method that
    failed on a ray has null intensity and errors there, "failed": true and its "failure" text;
    each case's "summary" counts the failed rays per method, and the top-level "failed" counts
    every failed method-ray. An invalid spec raises InputError before anything runs.

    A mesh of cells other than tetrahedra (hexahedra, wedges, pyramids, voxels, quadratic cells)
    is integrated in the cells' own interpolation, as `rayint eval` does ("mode": "own": one
    method, with its 50-digit reference; such cases go alone and take no methods);
    cells="split" integrates VTK's tetrahedralisation of them with the methods instead.
    """
    docs = [_document(c, "case") for c in (case if isinstance(case, (list, tuple)) else [case])]
    return json.loads(_rayint._evaluate(docs, _methods_csv(methods), bool(timing), int(threads), _split(cells)))


def reference(case, threads=0, cells="own"):
    """The independent 50-digit reference of every ray of a case: {"case": name, "rays": [...]},
    each ray as in `rayint eval`'s "reference" field (intensity, transmittance, error bound).
    A mesh of cells other than tetrahedra needs cells="split" here (its own-interpolation
    reference comes with evaluate())."""
    return json.loads(_rayint._reference(_document(case, "case"), int(threads), _split(cells)))


def check(case, candidate, rel_tol=1e-6, abs_tol=0.0, with_reference=True, threads=0, cells="own"):
    """`rayint check`: another renderer's per-ray intensities against the exact values.

    candidate: a path or a dict in the candidate format (docs/candidate-format.md). Returns the
    diff `rayint check` writes (a dict with "pass", "summary", "rays", ...). On a mesh of cells
    other than tetrahedra the expected values are the cells' own interpolation (one per camera
    pixel or ray, as `rayint check`); cells="split": VTK's tetrahedralisation."""
    text, _ = _rayint._check(_document(case, "case"), _document(candidate, "candidate"),
                             float(rel_tol), float(abs_tol), bool(with_reference), int(threads), _split(cells))
    return json.loads(text)


def integrate(method, case, length=None, scalar_far=None, scalar_exit=None, background=None):
    """Any method, by its spec string, with the transfer functions of `case` (path or dict).

    Without arrays: the case's own rays. With arrays: length, scalar_far, scalar_exit of shape
    (rays, segments) (1-D: one ray), segments ordered from the far end toward the eye, and
    background (rays, 3) or (3,) (default black). Returns (intensity, transmittance), each of
    shape (rays, 3).
    """
    doc = _document(case, "case")
    if length is None and scalar_far is None and scalar_exit is None:
        empty = np.zeros((0, 0))
        return _rayint._integrate(method, doc, empty, empty, empty, np.zeros((0, 3)), False)
    if length is None or scalar_far is None or scalar_exit is None:
        raise ValueError("integrate: give length, scalar_far and scalar_exit together")
    length, scalar_far, scalar_exit = np.broadcast_arrays(
        *(np.atleast_2d(np.asarray(a, dtype=np.float64)) for a in (length, scalar_far, scalar_exit)))
    rays = length.shape[0]
    bg = np.zeros((rays, 3)) if background is None else np.asarray(background, dtype=np.float64)
    bg = np.broadcast_to(bg, (rays, 3))
    return _rayint._integrate(method, doc, *(np.ascontiguousarray(a) for a in
                                             (length, scalar_far, scalar_exit, bg)), True)


def method_names():
    """The registered methods ("exact", "paper", "riemann", ..., "nerf", "pl_nerf")."""
    return list(_rayint._method_names())


def methods():
    """The method table `rayint methods --format json` prints: every method with its parameters
    (name, type, default, allowed values), the table method specs are validated against."""
    return json.loads(_rayint._methods_json())["methods"]


def nerf_deltas(t, last="1e10"):
    """NeRF's interval lengths for sample positions t (..., N), from the eye outward:
    delta_i = t_{i+1} - t_i, and for the last sample 1e10 (last="1e10", NeRF 2020's
    run_nerf.py) or 0 (last="none": the ray ends at the last sample)."""
    t = np.asarray(t, dtype=np.float64)
    fill = {"1e10": 1e10, "none": 0.0}
    if last not in fill:
        raise ValueError(f"nerf_deltas: last must be '1e10' or 'none', got {last!r}")
    return np.concatenate([np.diff(t, axis=-1), np.full(t.shape[:-1] + (1,), fill[last])], axis=-1)


def _samples(sigma, rgb):
    sigma = np.asarray(sigma, dtype=np.float64)
    rgb = np.asarray(rgb, dtype=np.float64)
    if sigma.ndim < 1 or rgb.shape != sigma.shape + (3,):
        raise ValueError(f"sigma must have shape (..., N) and rgb (..., N, 3); got {sigma.shape} "
                         f"and {rgb.shape}")
    batch = sigma.shape[:-1]
    n = sigma.shape[-1]
    s2 = np.ascontiguousarray(sigma.reshape(-1, n))
    c3 = np.ascontiguousarray(np.moveaxis(rgb.reshape(-1, n, 3), -1, -2))
    return batch, n, s2, c3


def nerf_composite(sigma, rgb, delta, background=None):
    """NeRF's quadrature (Mildenhall et al. 2020, Eq. 3) on explicit samples, from the eye out:
    C = sum_i T_i (1 - exp(-sigma_i delta_i)) c_i (+ T_N background), T_i = prod_{j<i}(1 - alpha_j).

    sigma (..., N), rgb (..., N, 3), delta (..., N) (see nerf_deltas for NeRF 2020's). Returns
    (rgb (..., 3), transmittance (..., 3)); the C++ code of the `nerf` method (integrators/nerf).
    """
    batch, n, s2, c3 = _samples(sigma, rgb)
    d2 = np.ascontiguousarray(np.broadcast_to(np.asarray(delta, dtype=np.float64),
                                              batch + (n,)).reshape(-1, n))
    out, trans = _rayint._composite(s2, c3, d2, False, True)
    return _finish(out, trans, batch, background)


def pl_nerf_composite(sigma, rgb, t, color="mid", background=None):
    """PL-NeRF's quadrature (Uy et al. 2023) on explicit samples at positions t (..., N), from the
    eye out: density linear between samples with its exact transmittance
    exp(-(sigma_i + sigma_{i+1})(t_{i+1} - t_i)/2), colour (c_i + c_{i+1})/2 (color="mid") or
    c_i (color="near"), over [t_0, t_{N-1}]. Returns (rgb (..., 3), transmittance (..., 3)).
    """
    if color not in ("mid", "near"):
        raise ValueError(f"pl_nerf_composite: color must be 'mid' or 'near', got {color!r}")
    batch, n, s2, c3 = _samples(sigma, rgb)
    t = np.broadcast_to(np.asarray(t, dtype=np.float64), batch + (n,)).reshape(-1, n)
    d2 = np.ascontiguousarray(np.diff(t, axis=-1))
    out, trans = _rayint._composite(s2, c3, d2, True, color == "mid")
    return _finish(out, trans, batch, background)


def _finish(out, trans, batch, background):
    out = out.reshape(batch + (3,))
    trans = trans.reshape(batch + (3,))
    if background is not None:
        out = out + trans * np.asarray(background, dtype=np.float64)
    return out, trans
