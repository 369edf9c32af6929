"""What the report scripts under reports/ start with, once: the repository root, the build
directory (argv[1], default build/), the rayint executable in it, matplotlib without a display,
and `rayint slab` runs read as JSON.

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
    from report_env import BUILD, RAYINT, ROOT, plt, slab  # noqa: E402
"""
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
RAYINT = os.path.join(BUILD, "rayint")


def slab(args, method):
    """`rayint slab --method METHOD --no-integral-equation ARGS`, its JSON report."""
    cmd = [RAYINT, "slab", "--method", method, "--no-integral-equation"] + args
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
