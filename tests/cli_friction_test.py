#!/usr/bin/env python3
"""CTest `cli_friction`: what a newcomer hits first (issue 26), through the real executable.

- output folders (`check --artifacts`, `gate --write-baseline`, `stress --worst-dir`) are created
  when missing; "exists and is not a directory" only when a file is in the way; a missing
  `gate --baseline` is "no such directory";
- `check --candidate-image` without --artifacts writes nothing into the working directory;
- integer options take `1e3`-style forms (same report as `1000`), and refuse `1.5`;
- progress on a pipe has no carriage returns, and -q silences render, slab and stress alike;
- `render --fit` frames a mesh that has no camera: every border pixel is background, and the
  mesh covers a good share of the image;
- `eval` on a camera case warns about the 50-digit reference and names --no-reference;
- `scripts/run.sh` builds only the `rayint_cli` target (cmake replaced by a logger on PATH).

Usage: cli_friction_test.py SOURCE_DIR RAYINT_EXE
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

source, exe = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
failures = []


def run(args, cwd, timeout=600):
    r = subprocess.run([exe] + args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True, timeout=timeout)
    return r.returncode, r.stdout, r.stderr


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


with tempfile.TemporaryDirectory(prefix="rayint-friction-") as tmp:
    shutil.copytree(os.path.join(source, "cases"), os.path.join(tmp, "cases"))
    shutil.copytree(os.path.join(source, "docs", "examples"), os.path.join(tmp, "examples"))
    case = "cases/mesh-ball-radial.json"

    # Output folders, created when missing.
    status, _, err = run(["render", case, "-o", "exact.npy", "-q"], tmp)
    check(status == 0 and err == "", "render -q: exit 0, nothing on stderr")
    before = sorted(os.listdir(tmp))
    status, out, err = run(["check", case, "--candidate-image", "exact.npy", "--rel-tol", "1e-12", "-q"], tmp)
    check(status == 0 and json.loads(out)["heat_map"] is None, "check without --artifacts: exit 0, heat_map null")
    check(sorted(os.listdir(tmp)) == before, "check without --artifacts writes nothing into the working directory")
    status, out, err = run(["check", case, "--candidate-image", "exact.npy", "--artifacts", "a/b/c", "-q"], tmp)
    check(status == 0 and os.path.isfile(os.path.join(tmp, "a/b/c/error_heat_map.png")),
          "check --artifacts a/b/c: created, heat map written")
    open(os.path.join(tmp, "afile"), "w").close()
    status, _, err = run(["check", case, "--candidate-image", "exact.npy", "--artifacts", "afile", "-q"], tmp)
    check(status == 2 and err.strip().endswith("afile: --artifacts: exists and is not a directory")
          and err.count("\n") == 1, "check --artifacts FILE: exit 2, one line 'exists and is not a directory'")

    cand = {"case": "paper-figure-2", "rays": []}
    status, out, _ = run(["eval", "cases/paper-figure-2.json", "--methods", "exact", "--no-timing", "-q"], tmp)
    for ray in json.loads(out)["cases"][0]["rays"]:
        cand["rays"].append({"intensity": ray["methods"]["exact"]["intensity"]})
    json.dump(cand, open(os.path.join(tmp, "cand.json"), "w"))
    status, _, err = run(["gate", "--candidate", "cand.json", "--write-baseline", "new/base", "-q"], tmp)
    check(status == 0 and os.listdir(os.path.join(tmp, "new/base")), "gate --write-baseline new/base: created and written")
    status, _, err = run(["gate", "--candidate", "cand.json", "--baseline", "missing", "-q"], tmp)
    check(status == 2 and "missing: --baseline: no such directory" in err, "gate --baseline MISSING: exit 2, 'no such directory'")

    # Integer forms people type.
    status, a, _ = run(["stress", "--count", "1e3", "--seed", "2", "--regime", "thin", "--json", "-q"], tmp)
    status2, b, _ = run(["stress", "--count", "1000", "--seed", "2", "--regime", "thin", "--json", "-q"], tmp)
    check(status == 0 and status2 == 0 and a == b, "stress --count 1e3 == --count 1000, byte for byte")
    status, _, err = run(["stress", "--count", "1.5", "-q"], tmp)
    check(status == 2 and "--count" in err, "stress --count 1.5: exit 2 naming --count")
    status, out, err = run(["slab", "--tau", "1", "--albedo", "0.5", "--phase", "isotropic", "--mu0", "1",
                            "--mu-up", "0.5", "--method", "monte_carlo", "--photons", "2e4", "--seed", "1", "-q"], tmp)
    check(status == 0 and err == "", "slab --photons 2e4 -q: exit 0, nothing on stderr")

    # stress --worst-dir: created when missing; without it no worst files.
    status, _, _ = run(["stress", "--count", "200", "--regime", "thin", "-q", "--worst-dir", "w/x"], tmp)
    check(status == 0 and len(os.listdir(os.path.join(tmp, "w/x"))) > 0, "stress --worst-dir w/x: created and written")
    before = sorted(os.listdir(tmp))
    status, _, _ = run(["stress", "--count", "200", "--regime", "thin", "-q"], tmp)
    check(status == 0 and sorted(os.listdir(tmp)) == before, "stress without --worst-dir writes no files")

    # Progress on a pipe: plain lines.
    status, _, err = run(["render", case, "-o", "p.png"], tmp)
    check(status == 0 and "\r" not in err and "rows" in err, "render progress on a pipe: lines, no carriage return")

    # render --fit on a gmsh mesh without a camera.
    status, _, err = run(["render", "examples/gmsh-box.json", "--fit", "-o", "fit.npy"], tmp)
    check(status == 0 and '--fit: "camera"' in err, "render --fit: exit 0, prints the camera it used")
    if status == 0:
        import numpy as np
        img = np.load(os.path.join(tmp, "fit.npy"))
        lit = (np.abs(img).sum(axis=2) > 0)
        border = np.concatenate([lit[0, :], lit[-1, :], lit[:, 0], lit[:, -1]])
        print(f"     --fit image {img.shape[1]}x{img.shape[0]}: {lit.mean():.3f} of the pixels show the mesh, "
              f"{border.sum()} border pixels do")
        check(not border.any() and lit.mean() > 0.3, "render --fit: whole mesh inside the image and >30 % of it")

    # eval on a camera case: the warning comes before the reference runs.
    cam = json.load(open(os.path.join(source, "cases", "mesh-ball-radial.json")))
    cam.pop("rays", None)
    cam["mesh_file"] = os.path.join(source, "cases", cam["mesh_file"]) if "mesh_file" in cam else None
    if cam["mesh_file"] is None:
        cam.pop("mesh_file")
    cam["camera"]["width"], cam["camera"]["height"] = 32, 32
    json.dump(cam, open(os.path.join(tmp, "cam.json"), "w"))
    p = subprocess.Popen([exe, "eval", "cam.json"], cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        _, err = p.communicate(timeout=15)
    except subprocess.TimeoutExpired:
        p.kill()
        _, err = p.communicate()
    check("1024 rays" in err and "--no-reference" in err, "eval on a 32x32 camera case: warns, names --no-reference")

    # scripts/run.sh: only the executable is built.
    fake = os.path.join(tmp, "fakebin")
    os.makedirs(fake)
    log = os.path.join(tmp, "cmake.log")
    with open(os.path.join(fake, "cmake"), "w") as f:
        f.write(f'#!/bin/sh\necho "$@" >> {log}\n')
    os.chmod(os.path.join(fake, "cmake"), 0o755)
    build = os.path.join(tmp, "fakebuild")
    os.makedirs(build)
    with open(os.path.join(build, "rayint"), "w") as f:
        f.write("#!/bin/sh\necho rayint \"$@\"\n")
    os.chmod(os.path.join(build, "rayint"), 0o755)
    env = dict(os.environ, PATH=fake + os.pathsep + os.environ["PATH"], RAYINT_BUILD_DIR=build)
    r = subprocess.run([os.path.join(source, "scripts", "run.sh")], env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    calls = open(log).read().splitlines() if os.path.exists(log) else []
    builds = [c for c in calls if c.startswith("--build")]
    check(r.returncode == 0 and len(builds) == 1 and builds[0].endswith("--target rayint_cli")
          and "rayint eval cases --format table" in r.stdout,
          f"scripts/run.sh builds only rayint_cli, then evaluates cases/ (cmake calls: {calls})")
    # A failed method (exit 1 of rayint eval) is explained in one line, and the job still ran;
    # bad input (exit 2) is passed on.
    for code, want in ((1, 0), (2, 2)):
        with open(os.path.join(build, "rayint"), "w") as f:
            f.write(f"#!/bin/sh\necho rayint \"$@\"\nexit {code}\n")
        r = subprocess.run([os.path.join(source, "scripts", "run.sh")], env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
        explained = "FAILED" in r.stdout and "exits 1" in r.stdout
        check(r.returncode == want and (explained if code == 1 else not explained),
              f"scripts/run.sh with rayint eval exiting {code}: exits {r.returncode} (want {want})")

print(f"cli_friction: {len(failures)} failures")
sys.exit(1 if failures else 0)
