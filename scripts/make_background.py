#!/usr/bin/python3
"""Writes cases/scenes/ground.png: a small procedural 'aerial photograph' (fields, roads, a
river) to stand behind the cloud, like the aerial photo of Washington, DC behind Max's (1995)
cloud figures. Deterministic (numpy seed 1995); regenerate with
    /usr/bin/python3 scripts/make_background.py cases/scenes/ground.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

N = 256
rng = np.random.default_rng(1995)
img = np.zeros((N, N, 3))
# patchwork of fields on a slightly irregular grid
xs = np.sort(np.concatenate([[0, N], rng.integers(8, N - 8, 9)]))
ys = np.sort(np.concatenate([[0, N], rng.integers(8, N - 8, 9)]))
palette = np.array([[0.42, 0.55, 0.25], [0.55, 0.62, 0.30], [0.62, 0.55, 0.35], [0.35, 0.48, 0.22],
                    [0.70, 0.65, 0.45], [0.30, 0.42, 0.20], [0.50, 0.45, 0.30]])
for i in range(len(xs) - 1):
    for j in range(len(ys) - 1):
        c = palette[rng.integers(len(palette))] * rng.uniform(0.85, 1.1)
        img[ys[j]:ys[j + 1], xs[i]:xs[i + 1]] = c
# texture: per-pixel variation and furrows
yy, xx = np.mgrid[0:N, 0:N]
img *= (1 + 0.06 * rng.standard_normal((N, N, 1)))
img *= (1 + 0.04 * np.sin(xx * 0.9 + yy * 0.3))[..., None]
# roads along the field boundaries (a few of them) and a diagonal highway
for x in xs[1:-1][::2]:
    img[:, max(0, x - 1):x + 1] = [0.75, 0.74, 0.72]
for y in ys[1:-1][::3]:
    img[max(0, y - 1):y + 1, :] = [0.75, 0.74, 0.72]
hw = np.abs(yy - (0.6 * xx + 40)) < 1.5
img[hw] = [0.82, 0.80, 0.78]
# a river
cx = 150 + 30 * np.sin(yy / 40.0) + 10 * np.sin(yy / 13.0)
river = np.abs(xx - cx) < 5 + 2 * np.sin(yy / 21.0)
img[river] = [0.18, 0.30, 0.42]
# town blocks
for _ in range(40):
    x, y = rng.integers(20, 110, 2)
    w, h = rng.integers(3, 8, 2)
    img[y:y + h, x:x + w] = rng.uniform(0.55, 0.85) * np.array([1.0, 0.95, 0.9])
plt.imsave(sys.argv[1] if len(sys.argv) > 1 else "ground.png", np.clip(img, 0, 1))
