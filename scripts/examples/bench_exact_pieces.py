#!/usr/bin/python3
"""Throughput of rayint.exact_pieces from NumPy on 1,000,000 pieces, the pieces that
bench/bench_exact.cpp BM_exact_pieces_batch times in C++ (every stress regime in turn, seed 2026),
so the two figures compare the binding's overhead and nothing else. Times are the median
thread CPU time (and wall time) over --repeat calls, after one warm-up call.

usage: PYTHONPATH=build/python /usr/bin/python3 scripts/examples/bench_exact_pieces.py [--repeat 7]
C++:   build/bench/rayint_bench --benchmark_filter=BM_exact_pieces_batch --benchmark_repetitions=5
"""
import argparse
import json
import statistics
import sys
import time

import rayint
from rayint import _rayint


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=1000000)
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args(argv[1:])
    arrays = _rayint._mixed_regime_pieces(args.count, 2026)
    rayint.exact_pieces(*arrays)  # warm-up
    wall, cpu = [], []
    for _ in range(args.repeat):
        start, start_cpu = time.perf_counter(), time.thread_time()
        rayint.exact_pieces(*arrays)
        cpu.append(time.thread_time() - start_cpu)
        wall.append(time.perf_counter() - start)
    # CPU time of this thread (what Google Benchmark's "CPU" column is): on a shared machine the
    # wall time also counts the time other processes held the core.
    median = statistics.median(cpu)
    print(json.dumps({"pieces": args.count, "repeat": args.repeat,
                      "median_cpu_seconds": median, "median_wall_seconds": statistics.median(wall),
                      "ns_per_piece_cpu": median / args.count * 1e9,
                      "ns_per_piece_wall": statistics.median(wall) / args.count * 1e9,
                      "pieces_per_second_cpu": args.count / median}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
