#!/usr/bin/python3
"""Writes a large case file: one ray of N segments (default 2,000,000: 88 MB), for
measuring how `rayint eval` scales with the size of one case (README "One large case").

The scalar at the cell faces follows s_k = 0.5 + 0.45 sin(0.0037 k), rounded to 4 decimals,
so consecutive segments keep crossing the transfer-function breakpoints; lengths cycle through
1.0e-6 .. 1.9e-6 (total length ~ 2.9 for 2M segments, tau ~ 1.7: the background still shows).
Deterministic: the same N gives the same bytes.

usage: make_big_case.py OUT.json [--segments N]
"""
import argparse
import math


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--segments", type=int, default=2_000_000)
    a = ap.parse_args()
    n = a.segments
    if n < 1:
        ap.error("--segments must be >= 1")
    with open(a.out, "w") as f:
        f.write('{\n  "name": "big-one-ray",\n')
        f.write('  "description": "one ray of %d segments (scripts/make_big_case.py)",\n' % n)
        f.write('  "transfer_function": {\n'
                '    "density": [[0, 0.2], [0.5, 1], [1, 0.4]],\n'
                '    "color": {"r": [[0, 0.9], [1, 0.3]], "g": [[0, 0.4], [0.6, 0.8], [1, 0.5]],'
                ' "b": [[0, 0.2], [1, 0.7]]}\n  },\n')
        f.write('  "rays": [{"background": [0.3, 0.5, 0.8], "segments": [\n')
        face = ["%.4f" % (0.5 + 0.45 * math.sin(0.0037 * k)) for k in range(n + 1)]
        lengths = ["%.1fe-6" % (1.0 + 0.1 * (k % 10)) for k in range(10)]
        chunk = []
        for k in range(n):
            chunk.append('{"length":%s,"scalar":[%s,%s]}%s\n'
                         % (lengths[k % 10], face[k], face[k + 1], "," if k + 1 < n else ""))
            if len(chunk) == 65536:
                f.write("".join(chunk))
                chunk = []
        f.write("".join(chunk))
        f.write("  ]}]\n}\n")


if __name__ == "__main__":
    main()
