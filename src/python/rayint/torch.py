"""Optional PyTorch bindings of the exact piece integral with exact gradients (issue 28).

    from rayint.torch import exact_pieces
    emission, transmittance = exact_pieces(rho_exit, rho_far, kappa_exit, kappa_far, length)
    intensity = exact_ray(length, scalar_far, scalar_exit, background, density, color)  # one ray

takes float64 tensors of one shape (CPU; broadcast first) and is differentiable in all five:
forward and backward are rayint.exact_grad (C++ integrators/exact_grad.hpp), so the gradient is
the exact one, not autodiff through a quadrature. Importing rayint never imports torch; only this
module does (Debian's python3-torch).
"""
import numpy as np
import torch

from . import exact_grad as _exact_grad
from . import exact_ray_grad as _exact_ray_grad

_INPUTS = ("rho_exit", "rho_far", "kappa_exit", "kappa_far", "length")


class ExactPieces(torch.autograd.Function):
    """(rho_exit, rho_far, kappa_exit, kappa_far, length) -> (emission, transmittance)."""

    @staticmethod
    def forward(ctx, rho_exit, rho_far, kappa_exit, kappa_far, length):
        args = [t.detach().cpu().numpy().astype(np.float64) for t in
                (rho_exit, rho_far, kappa_exit, kappa_far, length)]
        r = _exact_grad(*args)
        like = dict(dtype=rho_exit.dtype, device=rho_exit.device)
        ctx.d_emission = [torch.as_tensor(r["d_emission"][k], **like) for k in _INPUTS]
        ctx.d_transmittance = [torch.as_tensor(r["d_transmittance"][k], **like) for k in _INPUTS]
        return torch.as_tensor(r["emission"], **like), torch.as_tensor(r["transmittance"], **like)

    @staticmethod
    def backward(ctx, grad_emission, grad_transmittance):
        return tuple(grad_emission * de + grad_transmittance * dt
                     for de, dt in zip(ctx.d_emission, ctx.d_transmittance))


def exact_pieces(rho_exit, rho_far, kappa_exit, kappa_far, length):
    """Differentiable exact emission and transmittance of linear pieces (see the module doc)."""
    args = torch.broadcast_tensors(rho_exit, rho_far, kappa_exit, kappa_far, length)
    return ExactPieces.apply(*args)


class ExactRay(torch.autograd.Function):
    """A whole ray: (length, scalar_far, scalar_exit, background, 6 x (positions, values)) ->
    intensity (3,). Forward and backward are rayint.exact_ray_grad (C++ exact_ray_gradient)."""

    @staticmethod
    def forward(ctx, length, scalar_far, scalar_exit, background, *nodes):
        np_of = lambda t: t.detach().cpu().numpy().astype(np.float64)
        functions = [(np_of(nodes[2 * f]), np_of(nodes[2 * f + 1])) for f in range(6)]
        g = _exact_ray_grad(np_of(length), np_of(scalar_far), np_of(scalar_exit), np_of(background),
                            functions[:3], functions[3:])
        like = dict(dtype=length.dtype, device=length.device)
        ctx.g = {k: torch.as_tensor(g[k], **like) for k in ("background", "length", "scalar_far", "scalar_exit")}
        ctx.nodes = [torch.as_tensor(a, **like) for a in g["density"] + g["color"]]
        return torch.as_tensor(g["intensity"], **like)

    @staticmethod
    def backward(ctx, grad_intensity):
        g = ctx.g
        out = [g["length"] @ grad_intensity, g["scalar_far"] @ grad_intensity, g["scalar_exit"] @ grad_intensity,
               g["background"] * grad_intensity]
        for f in range(6):  # function f feeds channel f % 3 only
            w = grad_intensity[f % 3]
            out += [w * ctx.nodes[f][:, 0], w * ctx.nodes[f][:, 1]]
        return tuple(out)


def exact_ray(length, scalar_far, scalar_exit, background, density, color):
    """Differentiable exact intensity (3,) of one ray.

    Tensors (float64, CPU): segments far -> near (length, scalar_far, scalar_exit: shape (n,)),
    background (3,); density and color each one (positions, values) pair for all channels or a
    list of three (r, g, b). Differentiable in every tensor; a pair shared by the channels
    receives the sum of its three channels' gradients (autograd adds them)."""
    fs = []
    for f in (density, color):
        fs += list(f) * 3 if len(f) == 2 else [t for pair in f for t in pair]
    if len(fs) != 12:
        raise ValueError("exact_ray: density and color: one (positions, values) pair or three")
    return ExactRay.apply(length, scalar_far, scalar_exit, background, *fs)
