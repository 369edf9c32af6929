#!/usr/bin/python3
"""Mutation run (issue 30): damages the inputs of every subcommand and counts what rayint does.

  /usr/bin/python3 scripts/mutate.py RAYINT [--per-seed N] [--seed S] [--out reports/reliability]

For each seed input (a ray case, mesh cases, scenes, a slab scene, a ParaView preset,
a shard file, CLI options) it makes N damaged copies -- a field deleted, a number replaced by NaN,
+-inf, 1e308, -1, 0, 2^63, a huge count, a string, a nested array, the text truncated or a byte
flipped -- runs the subcommand that reads it (timeout 60 s, ulimit -v 4 GB) and classifies:
  ok (exit 0/1), refused (exit 2, exactly one line on stderr), multi-line (exit 2, not one line),
  crash (killed by a signal or another exit code), timeout.
Writes summary.json and summary.md to --out. Deterministic for a given --seed.
"""
import argparse, collections, copy, json, os, random, resource, shutil, subprocess, sys, tempfile

SRC = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUMBERS = [float("nan"), float("inf"), -float("inf"), 1e308, -1, 0, 2**63, 10**18, 1e-320, 0.5, 3e16]


def small_camera(doc):
    cam = doc.get("camera") if isinstance(doc, dict) else None
    if isinstance(cam, dict):
        cam["width"] = cam["height"] = 8
    return doc


def leaves(doc, path=()):
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield path + (k,), v
            yield from leaves(v, path + (k,))
    elif isinstance(doc, list):
        for i, v in enumerate(doc):
            yield path + (i,), v
            yield from leaves(v, path + (i,))


def set_at(doc, path, value, delete=False):
    node = doc
    for p in path[:-1]:
        node = node[p]
    if delete:
        del node[path[-1]]
    else:
        node[path[-1]] = value


def mutate_json(doc, rng):
    d = copy.deepcopy(doc)
    paths = [p for p, _ in leaves(d)]
    if not paths:
        return json.dumps(d)
    path = rng.choice(paths)
    kind = rng.randrange(6)
    if kind == 0:
        set_at(d, path, None, delete=True)
    elif kind in (1, 2):
        set_at(d, path, rng.choice(NUMBERS))
    elif kind == 3:
        set_at(d, path, rng.choice(["", "x", [], {}, [[[[1]]]], True]))
    elif kind == 4:
        value = d
        for p in path:
            value = value[p]
        if isinstance(value, list) and value:
            set_at(d, path, value * rng.choice([0, 2, 100]))
        else:
            set_at(d, path, rng.choice(NUMBERS))
    text = json.dumps(d, allow_nan=True)  # NaN/Infinity: not JSON, the reader must say so
    if kind == 5:
        b = bytearray(text.encode())
        if rng.random() < 0.5:
            b = b[: rng.randrange(len(b))]
        else:
            b[rng.randrange(len(b))] = rng.randrange(256)
        return bytes(b)
    return text.encode()


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))


def run(cmd, cwd):
    try:
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, timeout=60, preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return "timeout", ""
    err = p.stderr.decode(errors="replace")
    if p.returncode in (0, 1):
        return "ok", err
    if p.returncode == 2:
        return ("refused" if err.count("\n") == 1 and err.endswith("\n") else "multi-line"), err
    return "crash", err


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rayint")
    ap.add_argument("--per-seed", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(SRC, "reports", "reliability"))
    a = ap.parse_args()
    a.rayint = os.path.abspath(a.rayint)
    rng = random.Random(a.seed)
    work = tempfile.mkdtemp()
    shutil.copytree(os.path.join(SRC, "cases", "meshes"), os.path.join(work, "meshes"))
    shutil.copy(os.path.join(SRC, "cases", "scenes", "ground.png"), work)
    # (seed file, its JSON, the command with {f} for the damaged file)
    seeds = []
    def seed(rel, cmd, shrink=False):
        doc = json.load(open(os.path.join(SRC, rel)))
        seeds.append((rel, small_camera(doc) if shrink else doc, cmd))
    seed("cases/thin-pieces.json", ["eval", "{f}", "-q", "-o", "out.json"])
    seed("cases/mesh-inline-cube.json", ["eval", "{f}", "-q", "-o", "out.json"])
    seed("cases/mesh-ball-radial.json", ["render", "{f}", "-q", "-o", "out.png"], shrink=True)
    seed("cases/scenes/cloud-emission-absorption.json", ["render", "{f}", "-q", "-o", "out.png"], shrink=True)
    seed("cases/scenes/slab-disort-1b.json", ["slab", "--scene", "{f}", "-q", "--photons", "4096", "-o", "out.txt"])
    seed("fuzz/seeds/preset/colormap-0.json", ["tf", "import", "{f}", "-q", "-o", "out.json"])
    # a shard file of a small stress run
    subprocess.run([a.rayint, "stress", "--count", "20", "--shard", "0/1", "-o", os.path.join(work, "shard.json"), "-q"],
                   check=True)
    seeds.append(("stress shard file", json.load(open(os.path.join(work, "shard.json"))), ["merge", "{f}", "-o", "out.json"]))
    # options: a damaged number in place of each numeric option's value
    option_runs = [["render", "mesh-ball-radial.json", "-q", "-o", "out.png", "--exposure", "{v}"],
                   ["eval", "thin-pieces.json", "-q", "-o", "out.json", "--progress-every", "{v}"],
                   ["stress", "--count", "{v}", "-q", "-o", "out.json"],
                   ["slab", "--tau", "{v}", "--albedo", "0.5", "--phase", "isotropic", "--source", "beam", "--mu0", "1",
                    "--mu-up", "1", "--mu-down", "1", "--method", "monte_carlo", "--photons", "4096", "-q", "-o", "out.txt"],
                   ["slab", "--tau", "1", "--albedo", "0.5", "--phase", "isotropic", "--source", "beam", "--mu0", "1",
                    "--mu-up", "1", "--mu-down", "1", "--method", "monte_carlo", "--photons", "{v}", "-q", "-o", "out.txt"]]
    json.dump(small_camera(json.load(open(os.path.join(SRC, "cases/mesh-ball-radial.json")))),
              open(os.path.join(work, "mesh-ball-radial.json"), "w"))
    shutil.copy(os.path.join(SRC, "cases/thin-pieces.json"), work)

    counts = collections.Counter()
    by_seed = {}
    examples = collections.defaultdict(list)
    for name, doc, cmd in seeds:
        c = collections.Counter()
        for i in range(a.per_seed):
            path = os.path.join(work, "m%d.json" % i)
            open(path, "wb").write(mutate_json(doc, rng))
            verdict, err = run([a.rayint] + [x.replace("{f}", path) for x in cmd], work)
            c[verdict] += 1
            if verdict not in ("ok", "refused") and len(examples[verdict]) < 10:
                examples[verdict].append({"seed": name, "command": cmd, "stderr": err[-600:]})
        by_seed[name] = dict(c)
        counts.update(c)
    for cmd in option_runs:
        c = collections.Counter()
        for v in ["nan", "inf", "-inf", "1e400", "-1", "0", "1e308", "9223372036854775808", "1e18", "x", ""]:
            verdict, err = run([a.rayint] + [x.replace("{v}", v) for x in cmd], work)
            c[verdict] += 1
            if verdict not in ("ok", "refused") and len(examples[verdict]) < 10:
                examples[verdict].append({"seed": " ".join(cmd), "value": v, "stderr": err[-600:]})
        by_seed["option: %s %s" % (cmd[0], cmd[cmd.index("{v}") - 1])] = dict(c)
        counts.update(c)
    shutil.rmtree(work)
    os.makedirs(a.out, exist_ok=True)
    summary = {"command": "/usr/bin/python3 scripts/mutate.py " + " ".join(sys.argv[1:]),
               "runs": sum(counts.values()), "totals": dict(counts), "by_input": by_seed, "examples": examples}
    json.dump(summary, open(os.path.join(a.out, "summary.json"), "w"), indent=2)
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("# Mutation run (scripts/mutate.py)\n\n`%s`\n\n" % summary["command"])
        f.write("| input | ok (exit 0/1) | refused, one line (exit 2) | multi-line | crash | timeout |\n|---|---|---|---|---|---|\n")
        for k, c in by_seed.items():
            f.write("| %s | %d | %d | %d | %d | %d |\n" % (k, c.get("ok", 0), c.get("refused", 0), c.get("multi-line", 0),
                                                         c.get("crash", 0), c.get("timeout", 0)))
        f.write("| **total** | %d | %d | %d | %d | %d |\n" % tuple(counts.get(x, 0) for x in
                                                                 ("ok", "refused", "multi-line", "crash", "timeout")))
    print(json.dumps(summary["totals"]))
    return 1 if counts["crash"] or counts["multi-line"] else 0


if __name__ == "__main__":
    sys.exit(main())
