#!/usr/bin/env python3
"""CTest `python_pip_install`: `pip install .` packages the rayint module (pyproject.toml, setup.py).

The project's packaging files are copied to a temporary folder (so pip's in-tree build leaves no
egg-info or build/ in the source tree), pip installs from there with Debian's setuptools
(--no-build-isolation, --no-index: no network) into a --target folder, reusing this build
folder's compiled module (RAYINT_CMAKE_BUILD_DIR, so the test does not compile the library a
second time), and Debian's python3 then imports rayint from the target folder and computes.

Usage: pip_install_test.py SOURCE_DIR BUILD_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

source, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
with tempfile.TemporaryDirectory(prefix="rayint-pip-") as tmp:
    src = os.path.join(tmp, "src")
    os.makedirs(os.path.join(src, "src", "python", "rayint"))
    for f in ("pyproject.toml", "setup.py", "README.md", "LICENSE"):
        shutil.copy(os.path.join(source, f), src)
    shutil.copy(os.path.join(source, "src", "python", "rayint", "__init__.py"),
                os.path.join(src, "src", "python", "rayint"))
    site = os.path.join(tmp, "site")
    env = dict(os.environ, RAYINT_CMAKE_BUILD_DIR=build, PIP_NO_CACHE_DIR="1")
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-index",
                        "--no-deps", "--target", site, src], env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    print(r.stdout[-3000:])
    if r.returncode != 0:
        sys.exit("python_pip_install: pip install failed")
    code = ("import rayint, numpy as np; print(rayint.__file__); "
            "e, t = rayint.exact_pieces(np.array([1.0]), np.array([1.0]), np.array([1.0]), np.array([1.0]), np.array([1.0])); "
            "print(repr(float(e[0])), repr(float(t[0])))")
    r = subprocess.run([sys.executable, "-c", code], env=dict(os.environ, PYTHONPATH=site),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=tmp)
    print(r.stdout)
    if r.returncode != 0:
        sys.exit("python_pip_install: the installed module does not import")
    path, values = r.stdout.strip().split("\n")[-2:]
    if not path.startswith(site):
        sys.exit(f"python_pip_install: rayint was imported from {path}, not from the pip target {site}")
    # Constant density 1 and emission 1 over length 1: emission = 1 - e^-1, transmittance = e^-1.
    import math
    e, t = (float(x) for x in values.split())
    if abs(e - (1 - math.exp(-1))) > 1e-15 or abs(t - math.exp(-1)) > 1e-16:
        sys.exit(f"python_pip_install: exact_pieces gave {e}, {t}")
    leftovers = [p for p in ("rayint.egg-info", os.path.join("src", "python", "rayint.egg-info"))
                 if os.path.exists(os.path.join(source, p))]
    if leftovers:
        sys.exit(f"python_pip_install: left {leftovers} in the source tree")
print("python_pip_install: PASS")
