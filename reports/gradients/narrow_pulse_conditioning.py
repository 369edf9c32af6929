#!/usr/bin/python3
"""An independent check of one gradient entry, and how well conditioned it is (docs/gradients.md,
"Accuracy": the narrow_pulse rays far from the reference).

For a one-ray case file (here narrow-pulse-ray-1468.json, ray 1468 of gradchain_rays.hpp) and a
channel, computes in mpmath at 90 digits -- independently of rayint's closed forms and of its
50-digit reference gradient -- the intensity (each sub-piece between transfer-function nodes
integrated by mpmath.quad, composited far to near) and, by central differences with step 1e-40,
dI/d(position of density node K) and dI/d(each segment's end scalars). Then it moves each input
by one double ulp (2^-53 of the input's binade ~ 1.1e-16 near 0.75) and reports how much the
entry changes, relative to the channel's largest gradient entry: the change a double-precision
algorithm must be expected to make, since its inputs and intermediate positions carry that
rounding.

usage: narrow_pulse_conditioning.py CASE.json CHANNEL NODE SCALE
  CHANNEL r|g|b; NODE the density node whose position is differentiated; SCALE the channel's
  largest |entry| (from `rayint grad CASE`'s reference) for the relative figures.
"""
import copy
import json
import sys

import mpmath as mp

mp.mp.dps = 90
H = mp.mpf("1e-40")


def nodes(spec, ch):
    if isinstance(spec, dict):
        spec = spec[ch]
    return [[mp.mpf(x), mp.mpf(v)] for x, v in spec]


def value(fn, s):
    """Piecewise linear, constant beyond the end nodes."""
    if s <= fn[0][0]:
        return fn[0][1]
    if s >= fn[-1][0]:
        return fn[-1][1]
    for (x0, v0), (x1, v1) in zip(fn, fn[1:]):
        if x0 <= s <= x1:
            return v1 if x1 == x0 else v0 + (v1 - v0) * (s - x0) / (x1 - x0)


def intensity(dens, col, segs, bg):
    """dI/dt = rho (kappa - I) from the far end (background bg) to the eye."""
    I = bg
    for L, s_far, s_near in segs:
        cuts = {mp.mpf(0), mp.mpf(1)}
        if s_near != s_far:
            for x, _ in dens + col:
                u = (x - s_far) / (s_near - s_far)
                if 0 < u < 1:
                    cuts.add(u)
        cuts = sorted(cuts)
        for u0, u1 in zip(cuts, cuts[1:]):
            w = u1 - u0
            um = (u0 + u1) / 2  # both functions are linear on [u0, u1]: value at the middle, slope from the ends
            def lin(fn):
                a, m, b = (value(fn, s_far + (s_near - s_far) * u) for u in (u0, um, u1))
                return m, (b - a) / w
            rho_m, rho_s = lin(dens)
            k_m, k_s = lin(col)
            rho = lambda v: rho_m + rho_s * (v - w / 2)           # v in [0, w], u = u0 + v
            depth = lambda v: (rho_m * (w - v) + rho_s * ((w / 2) ** 2 - (v - w / 2) ** 2) / 2) * L  # from v to u1
            emission = mp.quad(lambda v: (k_m + k_s * (v - w / 2)) * rho(v) * L * mp.exp(-depth(v)), [0, w])
            I = I * mp.exp(-depth(0)) + emission
    return I


def derivative(dens, col, segs, bg, move):
    out = []
    for sign in (1, -1):
        d, s = copy.deepcopy(dens), copy.deepcopy(segs)
        move(d, s, sign * H)
        out.append(intensity(d, col, s, bg))
    return (out[0] - out[1]) / (2 * H)


def main():
    path, ch, k, scale = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    case = json.load(open(path))
    tf, ray, c = case["transfer_function"], case["rays"][0], "rgb".index(ch)
    dens, col = nodes(tf["density"], ch), nodes(tf["color"], ch)
    segs = [[mp.mpf(s["length"]), mp.mpf(s["scalar"][0]), mp.mpf(s["scalar"][1])] for s in ray["segments"]]
    bg = mp.mpf(ray["background"][c])
    print("I_%s = %s" % (ch, mp.nstr(intensity(dens, col, segs, bg), 20)))

    def node_pos(d, s, e):
        d[k][0] += e
    base = derivative(dens, col, segs, bg, node_pos)
    print("dI_%s/d(density node %d position) = %s" % (ch, k, mp.nstr(base, 15)))
    for j in range(len(segs)):
        for end, name in ((1, "far"), (2, "near")):
            def end_scalar(d, s, e, j=j, end=end):
                s[j][end] += e
            print("dI_%s/d(segment %d %s scalar) = %s" % (ch, j, name, mp.nstr(derivative(dens, col, segs, bg, end_scalar), 15)))
    print("one ulp moved: change of the node-%d entry, relative to the channel's largest entry %.6g" % (k, scale))
    for i in range(len(dens)):
        d = copy.deepcopy(dens)
        d[i][0] += mp.ldexp(1, int(mp.floor(mp.log(abs(d[i][0]), 2))) - 52) if d[i][0] != 0 else 0
        print("  density node %d position + 1 ulp: %.3g" % (i, abs(derivative(d, col, segs, bg, node_pos) - base) / scale))
    for j in range(len(segs)):
        for end, name in ((1, "far"), (2, "near")):
            s = copy.deepcopy(segs)
            s[j][end] += mp.ldexp(1, int(mp.floor(mp.log(abs(s[j][end]), 2))) - 52) if s[j][end] != 0 else 0
            print("  segment %d %s scalar + 1 ulp: %.3g" % (j, name, abs(derivative(dens, col, s, bg, node_pos) - base) / scale))


if __name__ == "__main__":
    main()
