#!/usr/bin/python3
"""Load CPU of rayint binaries, interleaved (issue 33).

The load is what scripts/scaling.py calls it: user + system CPU (the process's own rusage) of
`rayint render CASE -o OUT.png -q` on a 16 x 16 case, i.e. reading, checking and preparing the
mesh plus a negligible render. Each round runs every format with every binary in turn; printed:
the median and minimum per binary and format, in ms and in µs per tet, and the load average.

usage: load_ab.py --tets N --cases DIR/load-13-{fmt}.json --formats vtk vtu msh
                  [--rounds 9] [--out /tmp/load_ab.png] BINARY [BINARY ...]
"""
import argparse
import os
import statistics
import subprocess


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binaries", nargs="+")
    ap.add_argument("--cases", required=True, help="case path with {fmt} for the format")
    ap.add_argument("--formats", nargs="+", default=["vtk", "vtu", "msh"])
    ap.add_argument("--tets", type=int, required=True)
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--out", default="/tmp/load_ab.png")
    a = ap.parse_args()
    cpu = {(b, f): [] for b in a.binaries for f in a.formats}
    for _ in range(a.rounds):
        for f in a.formats:
            for b in a.binaries:
                p = subprocess.Popen([b, "render", a.cases.format(fmt=f), "-o", a.out, "-q"])
                _, status, ru = os.wait4(p.pid, 0)
                if status != 0:
                    raise SystemExit(f"{b} on {f}: exit status {status}")
                cpu[(b, f)].append(ru.ru_utime + ru.ru_stime)
    for f in a.formats:
        for b in a.binaries:
            s = cpu[(b, f)]
            med = statistics.median(s)
            print(f"{f} {b}: median {1e3 * med:.1f} ms = {1e6 * med / a.tets:.3f} us/tet, min {1e3 * min(s):.1f} ms")
    with open("/proc/loadavg") as fh:
        print("load average:", fh.read().strip())


if __name__ == "__main__":
    main()
