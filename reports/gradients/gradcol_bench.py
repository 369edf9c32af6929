#!/usr/bin/python3
# usage: gradcol_bench.py rounds filter label=binary ...  -> CPU-time medians per round per label
# (CPU medians with one decimal, and the mesh image loss / render ratios when those ran; the mesh
# benchmarks from build/bench: they read ../../cases/)
import json, subprocess, sys, statistics, os
rounds = int(sys.argv[1]); filt = sys.argv[2]
bins = [a.split('=', 1) for a in sys.argv[3:]]
res = {}
for r in range(rounds):
    for label, b in bins:
        out = subprocess.run([b, '--benchmark_filter=' + filt, '--benchmark_min_time=0.5', '--benchmark_repetitions=5',
                              '--benchmark_format=json'], capture_output=True, text=True).stdout
        for bm in json.loads(out)['benchmarks']:
            if bm.get('run_type') != 'iteration': continue
            res.setdefault((r, label, bm['run_name']), []).append(bm['cpu_time'])
    print('round', r, 'load', open('/proc/loadavg').read().split()[:3], flush=True)
names = sorted({k[2] for k in res})
for r in range(rounds):
    for label, _ in bins:
        med = {n: statistics.median(res[(r, label, n)]) for n in names if (r, label, n) in res}
        line = ' '.join(f'{n}={v:.1f}' for n, v in med.items())
        rat = []
        for s in ('0', '1'):
            g, f = med.get('BM_exact_grad_prepared/' + s), med.get('BM_exact_ray/' + s)
            if g and f: rat.append(f'set{s} {g/f:.3f}x')
            g, f = med.get('BM_exact_grad/' + s), med.get('BM_exact_ray_unprepared/' + s)
            if g and f: rat.append(f'free{s} {g/f:.3f}x')
        g0, g1 = med.get('BM_mesh_loss_gradient_image/0/process_time'), med.get('BM_mesh_loss_gradient_image/1/process_time')
        f = med.get('BM_mesh_render_image/process_time')
        if g0 and g1 and f: rat.append(f'mesh loss/render scalars {g0/f:.2f}x positions {g1/f:.2f}x')
        print(f'r{r} {label}: ' + ' '.join(rat) + ' | ' + line, flush=True)
