#!/usr/bin/python3
"""The Python module's figures for reports/nerf/README.md (issue 15):

1. bit for bit: `rayint eval CASE --methods M --no-timing` (CLI, JSON) against
   rayint.evaluate(CASE, methods=M, timing=False) (module), case by case over cases/;
2. rayint.exact_pieces against the independent 50-digit reference (rayint.reference on each piece
   written as a one-segment case), on the benchmark's mixed pieces, by regime; pieces whose
   reference is below the underflow floor 1e-290 (core/statistics.hpp) are scored by absolute
   error, as `rayint stress` does.

usage: PYTHONPATH=build/python /usr/bin/python3 reports/nerf/measure_module.py [--pieces 2400]
       [--cli build/rayint] [-o reports/nerf/module.json]
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

import rayint
from rayint import _rayint

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FLOOR = 1e-290


def piece_case(rho_exit, rho_far, kappa_exit, kappa_far, length):
    return {"name": "piece",
            "transfer_function": {"density": [[0.0, rho_far], [1.0, rho_exit]],
                                  "color": [[0.0, kappa_far], [1.0, kappa_exit]]},
            "rays": [{"segments": [{"length": length, "scalar": [0.0, 1.0]}]}]}


def bit_for_bit(cli, methods):
    cases = sorted(f for f in os.listdir(os.path.join(ROOT, "cases"))
                   if f.endswith(".json") and f != "gates.json")
    rows = []
    for name in cases:
        path = os.path.join(ROOT, "cases", name)
        start = time.time()
        r = subprocess.run([cli, "eval", path, "--methods", methods, "--no-timing"],
                           capture_output=True, text=True, check=True)
        from_cli = json.loads(r.stdout)
        from_module = rayint.evaluate(path, methods=methods, timing=False)
        numbers = 0
        for ray in from_cli["cases"][0]["rays"]:
            for m in ray["methods"].values():
                numbers += len(m["intensity"]) + len(m["transmittance"])
        rows.append({"case": name, "identical": from_cli == from_module,
                     "rays": len(from_cli["cases"][0]["rays"]), "numbers": numbers,
                     "seconds": time.time() - start})
    return rows


def against_reference(count, seed):
    names = _rayint._regime_names()
    arrays = _rayint._mixed_regime_pieces(count, seed)
    emission, transmittance = rayint.exact_pieces(*arrays)
    per = {n: {"pieces": 0, "max_rel": 0.0, "max_rel_emission": 0.0, "max_rel_transmittance": 0.0,
               "underflow": 0, "max_abs_underflow": 0.0} for n in names}
    for i in range(count):
        p = [float(a[i]) for a in arrays]
        ref = rayint.reference(piece_case(*p))["rays"][0]
        row = per[names[i % len(names)]]
        row["pieces"] += 1
        for key, got, want in (("emission", emission[i], ref["intensity"][0]),
                               ("transmittance", transmittance[i], ref["transmittance"][0])):
            if abs(want) < FLOOR:
                row["underflow"] += 1
                row["max_abs_underflow"] = max(row["max_abs_underflow"], abs(got - want))
            else:
                e = abs(got - want) / abs(want)
                row["max_rel"] = max(row["max_rel"], e)
                row["max_rel_" + key] = max(row["max_rel_" + key], e)
    return per


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--pieces", type=int, default=2400)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--cli", default=os.path.join(ROOT, "build", "rayint"))
    ap.add_argument("--methods", default="exact,paper,nerf:n=64,pl_nerf:n=64,riemann:n=64")
    ap.add_argument("-o", "--output", default=os.path.join(ROOT, "reports", "nerf", "module.json"))
    args = ap.parse_args(argv[1:])
    bits = bit_for_bit(args.cli, args.methods)
    ref = against_reference(args.pieces, args.seed)
    report = {"methods": args.methods, "bit_for_bit": bits, "pieces_seed": args.seed,
              "exact_pieces_vs_reference": ref}
    with open(args.output, "w") as f:
        json.dump(report, f, indent=1)
    same = sum(r["identical"] for r in bits)
    print(f"bit for bit: {same} of {len(bits)} cases identical "
          f"({sum(r['numbers'] for r in bits)} intensities and transmittances, {args.methods})")
    worst = max(r["max_rel"] for r in ref.values())
    print(f"exact_pieces vs 50-digit reference: {args.pieces} pieces, max rel {worst:.3g}")
    for name, r in ref.items():
        print(f"  {name:<22} {r['pieces']:5d} pieces  max rel emission {r['max_rel_emission']:.2g}"
              f"  transmittance {r['max_rel_transmittance']:.2g}  "
              f"underflow {r['underflow']} (max abs {r['max_abs_underflow']:.2g})")
    return 0 if same == len(bits) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
