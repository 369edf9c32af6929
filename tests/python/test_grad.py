"""rayint.exact_grad and rayint.torch (issue 28): the values are exact_pieces', the derivatives
match central differences of exact_pieces, and the torch.autograd.Function passes
torch.autograd.gradcheck in double. The 50-digit accuracy of the derivatives is tested in C++
(tests/test_grad.cpp, [grad]); here the binding is.

Run by CTest (test `python_module`) with PYTHONPATH=<build>/python.
"""
import numpy as np
import os

import pytest

import rayint

INPUTS = ("rho_exit", "rho_far", "kappa_exit", "kappa_far", "length")


def pieces(seed=3, n=64):
    rng = np.random.default_rng(seed)
    # optical depths from thin to thick, both slopes, zero-density ends, on the branches of exact.cpp
    rho_exit = rng.uniform(0.0, 3.0, n) * 10.0 ** rng.uniform(-3, 1.5, n)
    rho_far = rng.uniform(0.0, 3.0, n) * 10.0 ** rng.uniform(-3, 1.5, n)
    rho_far[::7] = 0.0
    kappa_exit = rng.uniform(0.0, 2.0, n)
    kappa_far = rng.uniform(0.0, 2.0, n)
    length = rng.uniform(0.1, 2.0, n)
    return rho_exit, rho_far, kappa_exit, kappa_far, length


def test_exact_grad_values_are_exact_pieces():
    args = pieces()
    g = rayint.exact_grad(*args)
    e, t = rayint.exact_pieces(*args)
    np.testing.assert_allclose(g["emission"], e, rtol=1e-13, atol=0.0)
    np.testing.assert_allclose(g["transmittance"], t, rtol=1e-13, atol=0.0)


def test_exact_grad_matches_central_differences():
    args = [np.array(a) for a in pieces()]
    g = rayint.exact_grad(*args)
    for k, name in enumerate(INPUTS):
        h = 1e-6 * np.maximum(1.0, np.abs(args[k]))
        up = [a.copy() for a in args]
        down = [a.copy() for a in args]
        up[k] = args[k] + h
        down[k] = np.maximum(args[k] - h, 0.0)  # rho, length stay >= 0 (one-sided there)
        step = up[k] - down[k]
        e_up, t_up = rayint.exact_pieces(*up)
        e_down, t_down = rayint.exact_pieces(*down)
        for key, fd in (("d_emission", (e_up - e_down) / step), ("d_transmittance", (t_up - t_down) / step)):
            scale = np.maximum(1.0, np.abs(g[key][name]))
            # one-sided steps (at rho = 0) are first order: 1e-5; central ones ~1e-9
            tol = np.where(args[k] - h < 0.0, 1e-5, 1e-7)
            assert np.all(np.abs(g[key][name] - fd) <= tol * scale), (key, name)


def test_exact_grad_broadcasts_and_refuses_bad_input():
    g = rayint.exact_grad(1.0, 2.0, [0.5, 0.7], 1.0, 0.3)
    assert g["d_emission"]["kappa_exit"].shape == (2,)
    with pytest.raises(ValueError):
        rayint.exact_grad(-1.0, 2.0, 0.5, 1.0, 0.3)


def test_torch_function_gradcheck():
    # scripts/test.sh installs torch and sets RAYINT_REQUIRE_TORCH: there the test runs or fails.
    if os.environ.get("RAYINT_REQUIRE_TORCH"):
        import torch
    else:
        torch = pytest.importorskip("torch")
    import rayint.torch as rt

    args = [torch.tensor(a[:12], dtype=torch.float64, requires_grad=True) for a in pieces(seed=5)]
    # away from rho = 0, where gradcheck's central differences would leave the domain
    with torch.no_grad():
        args[1] += 0.05
        args[0] += 0.05
    assert torch.autograd.gradcheck(rt.exact_pieces, tuple(args), eps=1e-6, atol=1e-8, rtol=1e-6)


def test_module_imports_without_torch():
    # rayint's __init__ never imports torch
    import subprocess
    import sys

    code = "import sys; sys.modules['torch'] = None; import rayint; print(len(rayint.exact_grad(1, 1, 1, 1, 1)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


def _torch():
    if os.environ.get("RAYINT_REQUIRE_TORCH"):
        import torch
    else:
        torch = pytest.importorskip("torch")
    return torch


def _ray_inputs(torch):
    """Three segments with transfer-function kinks inside, per-channel functions of 3-4 nodes."""
    t = lambda v: torch.tensor(v, dtype=torch.float64, requires_grad=True)
    length, s_far, s_exit = t([0.7, 0.45, 0.3]), t([0.0123, 0.8871, 0.3317]), t([0.8871, 0.3317, 0.9533])
    background = t([0.3, 0.1, 0.6])
    density = [(t([0.0, 0.43, 1.0]), t([0.3, 2.1, 0.7])), (t([0.0, 1.0]), t([0.5, 1.5])),
               (t([0.1, 0.61, 0.9]), t([1.0, 0.2, 2.5]))]
    color = [(t([0.0, 1.0]), t([0.9, 0.3])), (t([0.0, 0.57, 1.0]), t([0.4, 0.8, 0.5])),
             (t([0.0, 0.35, 0.7, 1.0]), t([0.2, 0.9, 0.1, 0.7]))]
    return length, s_far, s_exit, background, density, color


def test_exact_ray_grad_matches_central_differences_of_integrate():
    # The binding against central differences of the CLI's exact method on the same ray.
    torch = _torch()
    length, s_far, s_exit, bg, density, color = [x for x in _ray_inputs(torch)]
    np_ = lambda x: x.detach().numpy()
    dens = [(np_(p), np_(v)) for p, v in density]
    col = [(np_(p), np_(v)) for p, v in color]
    g = rayint.exact_ray_grad(np_(length), np_(s_far), np_(s_exit), np_(bg), dens, col)

    def intensity(L, f, e):
        return rayint.exact_ray_grad(L, f, e, np_(bg), dens, col)["intensity"]

    base = [np_(length).copy(), np_(s_far).copy(), np_(s_exit).copy()]
    for k, name in enumerate(("length", "scalar_far", "scalar_exit")):
        for j in range(3):
            up = [a.copy() for a in base]
            down = [a.copy() for a in base]
            up[k][j] += 1e-6
            down[k][j] -= 1e-6
            fd = (intensity(*up) - intensity(*down)) / 2e-6
            np.testing.assert_allclose(g[name][j], fd, rtol=0, atol=1e-7)


def test_torch_ray_function_gradcheck():
    torch = _torch()
    import rayint.torch as rt

    length, s_far, s_exit, bg, density, color = _ray_inputs(torch)
    flat = [length, s_far, s_exit, bg] + [x for pair in density + color for x in pair]

    def f(length, s_far, s_exit, bg, *nodes):
        d = [(nodes[2 * i], nodes[2 * i + 1]) for i in range(3)]
        c = [(nodes[6 + 2 * i], nodes[6 + 2 * i + 1]) for i in range(3)]
        return rt.exact_ray(length, s_far, s_exit, bg, d, c)

    assert torch.autograd.gradcheck(f, tuple(flat), eps=1e-6, atol=1e-8, rtol=1e-6)
    # A shared density (one pair for r, g, b) receives the sum of the three channels' gradients.
    p, v = density[0]
    out = rt.exact_ray(length, s_far, s_exit, bg, (p, v), color).sum()
    out.backward()
    assert torch.isfinite(v.grad).all() and v.grad.abs().max() > 0


def test_torch_ray_gradcheck_catches_a_wrong_backward():
    # The same gradcheck fails a backward with the two end scalars' derivatives swapped.
    torch = _torch()
    import rayint.torch as rt

    class Swapped(rt.ExactRay):
        @staticmethod
        def backward(ctx, grad_intensity):
            out = list(rt.ExactRay.backward(ctx, grad_intensity))
            out[1], out[2] = out[2], out[1]
            return tuple(out)

    length, s_far, s_exit, bg, density, color = _ray_inputs(torch)
    flat = [length, s_far, s_exit, bg] + [x for pair in density + color for x in pair]
    assert not torch.autograd.gradcheck(Swapped.apply, tuple(flat), eps=1e-6, atol=1e-8, rtol=1e-6,
                                        raise_exception=False)


def test_exact_ray_grad_refuses_bad_input():
    with pytest.raises(ValueError):
        rayint.exact_ray_grad([1.0], [0.2], [0.3], [0, 0, 0], ([0.5, 0.1], [1.0, 1.0]), ([0.0], [1.0]))
