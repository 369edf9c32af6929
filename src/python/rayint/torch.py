"""Optional PyTorch bindings of the exact piece integral with exact gradients (issue 28).

    from rayint.torch import exact_pieces
    emission, transmittance = exact_pieces(rho_exit, rho_far, kappa_exit, kappa_far, length)

takes float64 tensors of one shape (CPU; broadcast first) and is differentiable in all five:
forward and backward are rayint.exact_grad (C++ integrators/exact_grad.hpp), so the gradient is
the exact one, not autodiff through a quadrature. Importing rayint never imports torch; only this
module does (Debian's python3-torch).
"""
import numpy as np
import torch

from . import exact_grad as _exact_grad

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
