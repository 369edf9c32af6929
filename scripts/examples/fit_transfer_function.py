#!/usr/bin/python3
"""Optimise a transfer function to match a target image: exact gradients vs a Riemann renderer's.

The worked example of docs/gradients.md (issue 28). A 16 x 16 orthographic image of a ball whose
scalar is s = 1 - |x| (each pixel's chord cut into 6 segments with linear scalar, far -> near, as a
tetrahedral renderer hands them over). The target is the exact render with a "true" transfer
function (density shared by r, g, b; one colour function per channel; nodes at s = 0, 0.25, ...,
1). From a flat start, Adam fits the 20 node values twice, the same way, with:
  exact    rayint.torch.exact_pieces on the pieces between the (fixed) node positions (the exact
           piece integral; backward = its exact derivatives, C++), node interpolation and
           compositing in torch -- the same image as rayint.torch.exact_ray ray by ray (checked), and
  riemann  a Riemann renderer written in torch (n midpoint samples per segment, compositing
           I <- kappa (1 - e^{-rho h}) + e^{-rho h} I), differentiated by autograd.
Each fitted function is then rendered exactly: the loss it really achieves, and its distance to the
true node values.

Usage:
  /usr/bin/python3 scripts/examples/fit_transfer_function.py [--out DIR] [--check]
--out writes DIR/gradient_fit.png and DIR/gradient_fit.json (docs/figures/ holds one run);
--check (CTest `gradient_fit_example`) asserts what docs/gradients.md states about the run.
Needs rayint on PYTHONPATH and Debian's python3-torch.
"""
import argparse
import json
import math
import sys
import time

import numpy as np
import torch

import rayint.torch as rt

torch.set_default_dtype(torch.float64)
N_PIX, N_SEG, RIEMANN_N, STEPS, LR = 16, 6, 2, 300, 0.1
NODES = torch.tensor([0.0, 0.25, 0.5, 0.75, 1.0])
TRUE_DENSITY = torch.tensor([0.2, 2.5, 0.4, 4.0, 0.8])
TRUE_COLOR = torch.tensor([[0.9, 0.2, 0.1, 1.0, 0.3],    # r
                           [0.1, 0.8, 0.3, 0.2, 0.9],    # g
                           [0.4, 0.1, 0.9, 0.5, 0.2]])   # b
BACKGROUND = torch.tensor([0.05, 0.05, 0.1])


def rays():
    """Per pixel: (length, scalar_far, scalar_exit) of its segments far -> near, or None (miss)."""
    out = []
    for iy in range(N_PIX):
        for ix in range(N_PIX):
            x, y = -1 + (ix + 0.5) * 2 / N_PIX, -1 + (iy + 0.5) * 2 / N_PIX
            r2 = x * x + y * y
            if r2 >= 1.0:
                out.append(None)
                continue
            h = math.sqrt(1 - r2)
            z = np.linspace(-h, h, N_SEG + 1)  # far (z = -h) to near (z = +h)
            s = 1 - np.sqrt(r2 + z * z)
            out.append((np.diff(z), s[:-1], s[1:]))
    return out


RAYS = rays()
HIT = [i for i, r in enumerate(RAYS) if r is not None]
# Batched arrays for the Riemann renderer: every hit ray has N_SEG segments.
LEN = torch.tensor(np.array([RAYS[i][0] for i in HIT]))
S_FAR = torch.tensor(np.array([RAYS[i][1] for i in HIT]))
S_EXIT = torch.tensor(np.array([RAYS[i][2] for i in HIT]))


def interp(s, values):
    """Piecewise-linear function with nodes NODES and `values` at s (differentiable in values)."""
    k = torch.clamp(torch.searchsorted(NODES, s.contiguous(), right=True), 1, len(NODES) - 1)
    p0, p1 = NODES[k - 1], NODES[k]
    w = torch.clamp((s - p0) / (p1 - p0), 0.0, 1.0)
    return values[k - 1] * (1 - w) + values[k] * w


def split_pieces():
    """Every hit ray's segments split at the node positions (fixed; only node values are fitted),
    as (rays, max pieces) arrays far -> near, padded with zero-length pieces (transparent)."""
    rows = []
    for i in HIT:
        pieces = []
        for L, f, e in zip(*RAYS[i]):
            lo, hi = min(f, e), max(f, e)
            inside = [p for p in NODES.tolist() if lo < p < hi]
            ends = [f] + (inside if f < e else inside[::-1]) + [e]
            for a, b in zip(ends[:-1], ends[1:]):
                pieces.append((L * (b - a) / (e - f), a, b))
        rows.append(pieces)
    width = max(len(r) for r in rows)
    pad = lambda r: r + [(0.0, 0.0, 0.0)] * (width - len(r))
    arr = np.array([pad(r) for r in rows])  # (rays, width, 3): length, scalar far end, exit end
    return tuple(torch.tensor(arr[..., k]) for k in range(3))


P_LEN, P_FAR, P_EXIT = split_pieces()


def render_exact(density, color):
    """Exact: rayint.torch.exact_pieces on every piece (backward = the exact piece derivatives),
    node interpolation and compositing by torch (linear in the node values: exact too)."""
    rho_far, rho_exit = interp(P_FAR, density), interp(P_EXIT, density)
    out = []
    for c in range(3):
        emission, transmittance = rt.exact_pieces(rho_exit, rho_far, interp(P_EXIT, color[c]),
                                                  interp(P_FAR, color[c]), P_LEN)
        I = BACKGROUND[c].expand(P_LEN.shape[0]).clone()
        for j in range(P_LEN.shape[1]):  # far -> near
            I = I * transmittance[:, j] + emission[:, j]
        out.append(I)
    img = BACKGROUND.repeat(N_PIX * N_PIX, 1)
    return img.index_put((torch.tensor(HIT),), torch.stack(out, dim=1))


def render_exact_rays(density, color):
    """The same image ray by ray with rayint.torch.exact_ray (used once, to check the batch)."""
    rows = []
    for i in range(N_PIX * N_PIX):
        if RAYS[i] is None:
            rows.append(BACKGROUND)
            continue
        L, f, e = (torch.tensor(a) for a in RAYS[i])
        rows.append(rt.exact_ray(L, f, e, BACKGROUND, (NODES, density), [(NODES, color[c]) for c in range(3)]))
    return torch.stack(rows)


def render_riemann(density, color):
    u = (torch.arange(RIEMANN_N) + 0.5) / RIEMANN_N            # midpoints, from the far end
    s = S_FAR[..., None] + u * (S_EXIT - S_FAR)[..., None]      # (rays, segments, n)
    h = (LEN / RIEMANN_N)[..., None].expand_as(s)
    rho = interp(s, density)
    out = []
    for c in range(3):
        kappa = interp(s, color[c])
        I = BACKGROUND[c].expand(s.shape[0]).clone()
        a = torch.exp(-rho * h).reshape(s.shape[0], -1)         # far -> near, in order
        k = kappa.reshape(s.shape[0], -1)
        for j in range(a.shape[1]):
            I = k[:, j] * (1 - a[:, j]) + a[:, j] * I
        out.append(I)
    hit = torch.stack(out, dim=1)
    img = BACKGROUND.repeat(N_PIX * N_PIX, 1)
    img = img.index_put((torch.tensor(HIT),), hit)
    return img


def fit(render, target):
    """Adam on softplus-parametrised node values from a flat start; loss = sum (I - target)^2."""
    theta_d = torch.full((5,), math.log(math.expm1(1.0)), requires_grad=True)   # density 1
    theta_c = torch.full((3, 5), math.log(math.expm1(0.5)), requires_grad=True)  # colour 0.5
    opt = torch.optim.Adam([theta_d, theta_c], lr=LR)
    history = []
    for _ in range(STEPS):
        opt.zero_grad()
        density, color = torch.nn.functional.softplus(theta_d), torch.nn.functional.softplus(theta_c)
        loss = ((render(density, color) - target) ** 2).sum()
        loss.backward()
        opt.step()
        history.append(loss.item())
    with torch.no_grad():
        return torch.nn.functional.softplus(theta_d), torch.nn.functional.softplus(theta_c), history


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", help="write gradient_fit.png and gradient_fit.json here")
    ap.add_argument("--check", action="store_true", help="assert the statements of docs/gradients.md")
    args = ap.parse_args()
    with torch.no_grad():
        target = render_exact(TRUE_DENSITY, TRUE_COLOR)
        # The batched pieces and exact_ray (a whole ray, C++ exact_ray_gradient) agree.
        assert torch.allclose(target, render_exact_rays(TRUE_DENSITY, TRUE_COLOR), rtol=1e-13, atol=1e-15)
    results = {}
    for name, render in (("exact", render_exact), (f"riemann:n={RIEMANN_N}", render_riemann)):
        t0 = time.perf_counter()
        density, color, history = fit(render, target)
        seconds = time.perf_counter() - t0
        with torch.no_grad():
            img = render_exact(density, color)
            true_loss = ((img - target) ** 2).sum().item()
        results[name] = {
            "loss_history": history,
            "final_loss_own_renderer": history[-1],
            "final_loss_exact_render": true_loss,
            "max_node_error_density": (density - TRUE_DENSITY).abs().max().item(),
            "max_node_error_color": (color - TRUE_COLOR).abs().max().item(),
            "seconds": seconds,
            "image": img.reshape(N_PIX, N_PIX, 3).numpy(),
        }
        print(f"{name:11s} loss (own renderer) {history[0]:.3e} -> {history[-1]:.3e}; exact render of the fit: "
              f"loss {true_loss:.3e}; max |node - true|: density {results[name]['max_node_error_density']:.3f}, "
              f"color {results[name]['max_node_error_color']:.3f}; {seconds:.1f} s")
    ex, ri = results["exact"], results[f"riemann:n={RIEMANN_N}"]
    if args.out:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 4, figsize=(13, 3.8))
        show = lambda a, im, title: (a.imshow(np.clip(im, 0, 1), origin="lower"), a.set_title(title), a.axis("off"))
        show(ax[0], target.reshape(N_PIX, N_PIX, 3).numpy(), "target (exact, true TF)")
        show(ax[1], ex["image"], f"fit with exact gradients\nloss {ex['final_loss_exact_render']:.2e}")
        show(ax[2], ri["image"], f"fit with riemann:n={RIEMANN_N} gradients\n(rendered exactly) loss "
             f"{ri['final_loss_exact_render']:.2e}")
        ax[3].semilogy(ex["loss_history"], label="exact")
        ax[3].semilogy(ri["loss_history"], label=f"riemann:n={RIEMANN_N} (own render)")
        ax[3].set_xlabel("Adam step")
        ax[3].set_ylabel("loss")
        ax[3].legend()
        fig.tight_layout()
        fig.savefig(f"{args.out}/gradient_fit.png", dpi=90)
        with open(f"{args.out}/gradient_fit.json", "w") as f:
            json.dump({k: {kk: vv for kk, vv in v.items() if kk != "image"} for k, v in results.items()}, f, indent=1)
            f.write("\n")
    if args.check:
        # docs/gradients.md: the exact fit's loss falls by > 100x and ends below the Riemann fit's
        # (both rendered exactly), and its nodes are closer to the true ones.
        assert ex["final_loss_exact_render"] < ex["loss_history"][0] / 100, ex["final_loss_exact_render"]
        assert ex["final_loss_exact_render"] < ri["final_loss_exact_render"], (ex, ri)
        print("check: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
