#!/usr/bin/python3
"""Compare two outputs of gradbatch_compare.cpp (old, new): per gradient and channel, the largest
|new - old| over the channel's entries relative to the channel's largest |old| entry (NaN must stay
NaN), per kind (full, seg, psi); and the gradient's intensity against the forward exact's (batch
and scalar paths) in each output, relative.  Usage: gradbatch_compare.py OLD NEW"""
import struct
import sys


def val(h):
    return struct.unpack('<d', bytes.fromhex(h)[::-1])[0]


def blocks(path):
    cur = None
    fwd = {}
    last = None
    with open(path) as f:
        for line in f:
            p = line.split()
            if p[0] == 'G':
                if cur:
                    yield cur
                cur = {'kind': p[2], 'id': int(p[1]), 'I': {}, 'E': {0: [], 1: [], 2: []}, 'F': fwd}
            elif p[0] == 'F':
                if last != 'F':
                    fwd = {}
                fwd[int(p[1])] = (val(p[2]), val(p[3]))
            elif p[0] == 'I':
                cur['I'][int(p[1])] = val(p[2])
            elif p[0] in ('0', '1', '2'):
                cur['E'][int(p[0])].append(val(p[1]))
            last = p[0]
    if cur:
        yield cur


def rel(a, b, scale):
    if a == b:
        return 0.0
    if a != a or b != b:
        return float('inf')
    return abs(a - b) / scale if scale > 0 else float('inf')


old, new = sys.argv[1], sys.argv[2]
worst = {}
worst_int = {}
fwd_new = {'batch': 0.0, 'scalar': 0.0}
count = {}
for bo, bn in zip(blocks(old), blocks(new)):
    assert bo['kind'] == bn['kind'] and bo['id'] == bn['id'], (bo['id'], bn['id'])
    k = bo['kind']
    count[k] = count.get(k, 0) + 1
    for c in range(3):
        eo, en = bo['E'][c], bn['E'][c]
        assert len(eo) == len(en)
        finite = [abs(x) for x in eo if x == x]
        scale = max(finite + [abs(bo['I'].get(c, 0.0))]) if finite else 0.0
        for a, b in zip(eo, en):
            r = rel(a, b, scale) if not (a != a and b != b) else 0.0
            if r > worst.get(k, (0.0,))[0]:
                worst[k] = (r, bo['id'], c)
        io, inew = bo['I'].get(c), bn['I'].get(c)
        if io is not None:
            r = rel(io, inew, abs(io)) if io != 0 else (0.0 if inew == 0 else float('inf'))
            if r > worst_int.get(k, (0.0,))[0]:
                worst_int[k] = (r, bo['id'], c)
        if k in ('full', 'seg') and bn['F'] and c in bn['F'] and inew is not None:
            fb, fs = bn['F'][c]
            for name, f in (('batch', fb), ('scalar', fs)):
                r = 0.0 if f == inew else abs(inew - f) / abs(f)
                fwd_new[name] = max(fwd_new[name], r)
print('gradients compared:', count)
for k, w in sorted(worst.items()):
    print('%s: worst entry difference %.3g of the channel\'s largest entry (ray %d channel %d)' % (k, w[0], w[1], w[2]))
for k in count:
    if k not in worst:
        print('%s: every entry equal, bit for bit' % k)
for k, w in sorted(worst_int.items()):
    print('%s: worst intensity difference %.3g relative (ray %d channel %d)' % (k, w[0], w[1], w[2]))
print('new gradient intensity vs forward exact: batch path %.3g, scalar path %.3g (relative)' % (fwd_new['batch'], fwd_new['scalar']))
