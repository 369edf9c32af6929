#!/usr/bin/python3
"""Gradient error of the approximations across transfer-function jumps, from `rayint grad` JSON.

Usage (from the repository root; the command that made the files is in README.md here):
  /usr/bin/python3 reports/gradients/jumps/make_approx_table.py /tmp/sampled-jumps.grad.json reports/gradients/jumps

Writes approx_table.md: per method and ray, the gradient's max relative error against the exact
gradient (max over entries of |got - exact| / largest |exact| entry of the channel, worst
channel; `gradient_max_rel_vs_exact` of the report); the same without the jumps' position
entries (worst ray); the intensity's relative error against exact's (worst ray, worst channel);
on ray 1 the derivative with respect to the position of colour r's pure step (channel r) next
to exact's; and the worst entry over the rays.
"""
import json
import sys


def entries(g, c):
    """Channel c's entries of a gradient object as (name, value), in the report's layout."""
    ch = "rgb"[c]
    out = [("background", g["background"][c])]
    out += [(f"length[{j}]", l[c]) for j, l in enumerate(g["length"])]
    for j, s in enumerate(g["scalar"]):
        out += [(f"scalar_far[{j}]", s[0][c]), (f"scalar_exit[{j}]", s[1][c])]
    for f in ("density", "color"):
        for k, n in enumerate(g[f][ch]):
            out += [(f"{f} {ch}[{k}].position", n[0]), (f"{f} {ch}[{k}].value", n[1])]
    return out


def jump_position_names(case_file):
    """Names (as in entries()) of both position entries of every jump of the case's functions."""
    with open(case_file) as f:
        tf = json.load(f)["transfer_function"]
    names = set()
    for block in ("density", "color"):
        for ch in "rgb":
            nodes = tf[block][ch] if isinstance(tf[block], dict) else tf[block]
            for k in range(len(nodes) - 1):
                if nodes[k][0] == nodes[k + 1][0]:
                    names |= {f"{block} {ch}[{k}].position", f"{block} {ch}[{k + 1}].position"}
    return names


def error(got, exact, skip=lambda name: False):
    """Worst over channels of max |got - exact| / largest |exact| entry (entries skip(name) left
    out, the scale from all); with the worst entry."""
    worst = (0.0, "")
    for c in range(3):
        e, g = entries(exact, c), entries(got, c)
        scale = max(abs(v) for _, v in e) or 1.0
        for (name, want), (_, have) in zip(e, g):
            if skip(name):
                continue
            d = abs(have - want) / scale
            if d > worst[0]:
                worst = (d, f"{name} (channel {'rgb'[c]}): {have:.4g} vs {want:.4g}")
    return worst


def main(path, outdir):
    with open(path) as f:
        report = json.load(f)
    case = report["cases"][0]
    rays = case["rays"]
    jumps = jump_position_names(case["file"])
    labels = [l for l in rays[0]["methods"] if l != "exact"]
    fmt = lambda x: f"{x:.2g}"
    lines = ["| method | " + " | ".join(f"ray {r['index']}" for r in rays) +
             " | without jump positions and end scalars | intensity | ray 1: dI_r/d(step position) | worst entry (ray) |",
             "|" + "---|" * (len(rays) + 5)]
    exact_step = rays[1]["methods"]["exact"]["gradient"]["color"]["r"][0][0]
    lines.append("| exact | " + " | ".join("—" for _ in rays) + f" | — | — | {exact_step:.4g} | — |")
    for label in labels:
        cells, rest, worst_i, worst = [], 0.0, 0.0, (0.0, "")
        for r in rays:
            m, ex = r["methods"][label], r["methods"]["exact"]
            e = error(m["gradient"], ex["gradient"])
            cells.append(fmt(e[0]))
            if e[0] >= worst[0]:
                worst = (e[0], f"{e[1]} ({r['index']})")
            # The entries a jump's crossing does not move: background, lengths, node values, the
            # positions of nodes that are not jumps (the crossing term is in the jumps' positions
            # and in the segments' end scalars).
            rest = max(rest, error(m["gradient"], ex["gradient"], lambda n: n in jumps or n.startswith("scalar"))[0])
            worst_i = max(worst_i, max(abs(a - b) / abs(b) for a, b in zip(m["intensity"], ex["intensity"])))
        step = rays[1]["methods"][label]["gradient"]["color"]["r"][0][0]
        lines.append(f"| {label} | " + " | ".join(cells) +
                     f" | {fmt(rest)} | {fmt(worst_i)} | {step:.4g} | {worst[1]} |")
    with open(f"{outdir}/approx_table.md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
