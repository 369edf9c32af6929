"""Runs rayint on every file of the real-files corpus and counts what it accepts (issue 27).

  /usr/bin/python3 scripts/real-files/count.py RAYINT CORPUS [--jobs 2] [--timeout 60] [-o RESULTS.json]
  (scripts/real-files/count.sh RAYINT makes the corpus first and calls this)

CORPUS is a folder made by make-corpus.sh (its manifest.json). For every file:
  mesh      `rayint mesh info FILE --format json`, then `rayint eval CASE --methods exact
            --no-timing` on a mesh case naming the file with 6 rays through its bounding box and a
            transfer function over the field's range (VTK's reading); a file with cells other
            than tetrahedra is integrated in their own interpolation (rayint's default; eval takes
            no --methods then, so it is run without).
  image     `rayint render SCENE -o x.npy --stats s.json` of a scene whose grid medium names the
            file as shipped (no "array"), 5 explicit rays through the image's box, absorption +
            emission, method exact.
  colormap  `rayint tf import FILE` (one preset per file, as ParaView holds or exports it).
Outcome of each: "integrated" (exit 0, finite, some ray crossed the data), "integrated (own
interpolation)" (cells other than tetrahedra), "imported" (colour maps), "refused" (exit 2, one line on stderr `rayint: error:
FILE: ...`), or "unclear" (anything else: a crash, a signal, a time-out, exit 1, several lines, no
file name, a missing output, or no ray crossing the data: a bug or a suspicious answer, listed).
Cross-checks against VTK's (or meshio's) reading recorded by make-corpus.sh: cells by type (ghost
cells removed), the field's name; and within a family (one mesh or image written in many ways) the
spread of the rays' intensities. Prints a Markdown summary; -o writes every file's result.
"""
import argparse
import collections
import concurrent.futures
import json
import math
import os
import subprocess
import sys
import tempfile

RAYINT_TYPES = {"vertex": 1, "line": 3, "triangle": 5, "polygon": 7, "pixel": 8, "quad": 9, "tetra": 10, "voxel": 11,
                "hexahedron": 12, "wedge": 13, "pyramid": 14, "quadratic edge": 21, "quadratic triangle": 22,
                "quadratic quad": 23, "quadratic tetra": 24, "quadratic hexahedron": 25, "quadratic wedge": 26,
                "quadratic pyramid": 27, "biquadratic quad": 28, "triquadratic hexahedron": 29,
                "biquadratic-quadratic wedge": 32}


def run(cmd, timeout):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return "timeout", "", ""


def judge_refusal(rc, err, path):
    """'refused' with its line when rayint refused cleanly, else 'unclear' with why."""
    lines = [ln for ln in err.splitlines() if ln.strip()]
    if rc == "timeout":
        return "unclear", "time-out"
    if isinstance(rc, int) and rc < 0:
        return "unclear", "killed by signal %d" % -rc
    if rc != 2:
        return "unclear", "exit %s: %s" % (rc, " | ".join(lines[-3:]))
    if len(lines) != 1:
        return "unclear", "exit 2 with %d lines: %s" % (len(lines), " | ".join(lines[:3]))
    line = lines[0]
    stem = os.path.splitext(os.path.basename(path))[0]  # a TetGen .ele's error may name its .node
    if not line.startswith("rayint: error:") or (os.path.basename(path) not in line and stem + ".node" not in line):
        return "unclear", "exit 2, the line does not name the file: " + line
    return "refused", line


def rays_through(lo, hi, n):
    """n rays from outside the box through points near its centre, in fixed skew directions."""
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    d = math.sqrt(sum((b - a) ** 2 for a, b in zip(lo, hi))) or 1.0
    dirs = [(1, 0.13, 0.07), (-0.11, 1, 0.17), (0.09, -0.05, 1), (1, 1, 1), (-1, 0.6, -0.3), (0.3, -1, 0.7)][:n]
    offs = [(0, 0.05, -0.03), (0.04, 0, 0.02), (-0.06, 0.03, 0), (0.02, -0.04, 0.01), (0.1, 0.1, -0.1), (-0.08, 0.02, 0.05)]
    rays = []
    for (dx, dy, dz), off in zip(dirs, offs):
        norm = math.sqrt(dx * dx + dy * dy + dz * dz)
        u = (dx / norm, dy / norm, dz / norm)
        p = [c[k] + off[k] * (hi[k] - lo[k]) for k in range(3)]
        rays.append({"origin": [p[k] - 2 * d * u[k] for k in range(3)], "direction": list(u)})
    return rays, d


def field_range(entry):
    o = entry.get("oracle") or {}
    r = o.get("range")
    if r and math.isfinite(r[0]) and math.isfinite(r[1]):
        return (r[0], r[1]) if r[1] > r[0] else (r[0] - 0.5, r[0] + 0.5)
    return (0.0, 1.0)


def count_mesh(rayint, corpus, entry, tmp, timeout):
    path = os.path.join(corpus, entry["file"])
    res = {"file": entry["file"]}
    rc, out, err = run([rayint, "mesh", "info", path, "--format", "json"], timeout)
    if rc != 0:
        res["outcome"], res["detail"] = judge_refusal(rc, err, path)
        res["stage"] = "mesh info"
        return res
    try:
        info = json.loads(out)
    except ValueError:
        return dict(res, outcome="unclear", stage="mesh info", detail="exit 0, output is not JSON")
    res["info"] = {k: info.get(k) for k in ("points", "tets", "cells", "cells_by_type", "ghost_cells", "scalar", "skipped_cells")}
    lo, hi = info["bounds"]["min"], info["bounds"]["max"]
    rays, diag = rays_through(lo, hi, 6)
    a, b = field_range(entry)
    k = 3.0 / diag  # optical depth about 1-5 across the mesh
    case = {"name": "corpus", "mesh_file": path, "background": [0, 0, 0], "rays": rays,
            "transfer_function": {"density": [[a, 0.2 * k], [b, 1.5 * k]],
                                  "color": {"r": [[a, 1.0], [b, 0.2]], "g": [[a, 0.3], [b, 1.0]], "b": [[a, 0.1], [b, 0.9]]}}}
    res["rays"], res["tf"] = rays, case["transfer_function"]
    case_path = os.path.join(tmp, "case.json")
    with open(case_path, "w") as f:
        json.dump(case, f)
    out_path = os.path.join(tmp, "eval.json")
    # As a user runs it: tetrahedra (and straight tet10) by the exact method; a file with other
    # cells in their own interpolation, rayint's default, which is one method of its own (eval
    # then takes no --methods: asked with them it says so, and the case is run without).
    cmd = [rayint, "eval", case_path, "--no-timing", "-q", "-o", out_path]
    rc, _, err = run(cmd[:3] + ["--methods", "exact"] + cmd[3:], timeout)
    if rc == 2 and "--methods: the own interpolation" in err:
        rc, _, err = run(cmd, timeout)
    res["stage"] = "eval"
    if rc != 0:
        res["outcome"], res["detail"] = judge_refusal(rc, err, path)
        return res
    try:
        out = json.load(open(out_path))
        ev = out["cases"][0]
    except (OSError, ValueError, KeyError, IndexError):
        return dict(res, outcome="unclear", detail="exit 0, no eval JSON")
    own = out.get("mode") == "own"
    intens, hits, bad, rel = [], 0, [], []
    for i, r in enumerate(ev["rays"]):
        if own:  # cells other than tetrahedra (mesh/cell_traversal.hpp): per ray its chords
            hits += r.get("chords", 0) > 0
            if r.get("intensity") is None or r.get("abs_error") is None:
                bad.append(i)
            elif r.get("reference"):
                rel.append(r["abs_error"] / max(max(abs(v) for v in r["reference"]), 1e-300))
            intens.append(r.get("intensity"))
            continue
        m = r["methods"]["exact"]
        pieces = (r.get("reference") or {}).get("pieces", 0)
        hits += pieces > 0
        if m.get("failed") or not m.get("finite"):
            bad.append(r["index"])
        else:
            rel.append(max(m.get("rel_error") or [0]))
        intens.append(m.get("intensity"))
    res["intensities"] = intens
    res["rays_hitting"] = hits
    res["max_rel_error"] = max(rel, default=None)
    res["repairs"] = ev.get("mesh_repairs")
    if bad or hits == 0:
        res["outcome"] = "unclear"
        res["detail"] = "exit 0 but %s" % ("rays failed: %s" % bad if bad else "no ray crossed the mesh")
    else:
        res["outcome"] = "integrated (own interpolation)" if own else "integrated"
    return res


def count_image(rayint, corpus, entry, tmp, timeout):
    path = os.path.join(corpus, entry["file"])
    res = {"file": entry["file"], "stage": "render"}
    o = entry.get("oracle") or {}
    b = o.get("bounds") or [0, 1, 0, 1, 0, 1]
    lo, hi = [b[0], b[2], b[4]], [b[1], b[3], b[5]]
    rays, diag = rays_through(lo, hi, 5)
    a, z = field_range(entry)
    k = 3.0 / diag
    scene = {"name": "corpus", "medium": {"type": "grid", "grid_file": path},
             "transfer": {"extinction": [[a, 0.2 * k], [z, 1.5 * k]], "emission": [[a, 0.2], [z, 1.0]]},
             "background": {"color": [0, 0, 0]}, "effects": ["absorption", "emission"], "rays": rays,
             "methods": {"absorption": "exact", "emission": "exact"}}
    res["rays"], res["tf"] = rays, {"density": scene["transfer"]["extinction"],
                                    "color": {c: scene["transfer"]["emission"] for c in "rgb"}}
    scene_path = os.path.join(tmp, "scene.json")
    with open(scene_path, "w") as f:
        json.dump(scene, f)
    stats = os.path.join(tmp, "stats.json")
    rc, _, err = run([rayint, "render", scene_path, "-o", os.path.join(tmp, "img.npy"), "--stats", stats, "-q",
                      "--threads", "1"], timeout)
    if rc != 0:
        res["outcome"], res["detail"] = judge_refusal(rc, err, path)
        return res
    try:
        st = json.load(open(stats))
        pix = [r["pixel"] for r in st["rays"]]
    except (OSError, ValueError, KeyError):
        return dict(res, outcome="unclear", detail="exit 0, no stats JSON with rays")
    res["intensities"] = pix
    finite = all(math.isfinite(v) for p in pix for v in p)
    lit = sum(1 for p in pix if any(v > 0 for v in p))
    res["rays_hitting"] = lit
    if not finite or lit == 0:
        res["outcome"], res["detail"] = "unclear", "exit 0 but %s" % ("non-finite pixels" if not finite else "every ray black")
    else:
        res["outcome"] = "integrated"
    return res


def count_colormap(rayint, corpus, entry, tmp, timeout):
    path = os.path.join(corpus, entry["file"])
    res = {"file": entry["file"], "stage": "tf import", "name": entry["tool"]}
    rep = os.path.join(tmp, "report.json")
    rc, _, err = run([rayint, "tf", "import", path, "-q", "--report", rep, "-o", os.path.join(tmp, "tf.json")], timeout)
    if rc != 0:
        res["outcome"], res["detail"] = judge_refusal(rc, err, path)
        return res
    try:
        r = json.load(open(rep))
        res["color_space"] = r.get("color_space")
        res["max_deviation"] = max((r.get(k) or {}).get("max_deviation") or 0 for k in ("color", "density"))
        res["converged"] = all((r.get(k) or {}).get("converged", True) for k in ("color", "density"))
        res["log_scale"] = r.get("log_scale")
        res["opacity"] = r.get("opacity")
    except (OSError, ValueError):
        return dict(res, outcome="unclear", detail="exit 0, no import report")
    res["outcome"] = "imported" if res["converged"] else "unclear"
    return res


def cross_check(entry, res):
    """Differences between rayint's reading and VTK's/meshio's (cells by type, ghosts, the field)."""
    o, info = entry.get("oracle"), res.get("info")
    if not o or not info or "cells" not in o:
        return []
    notes = []
    mine = {}
    for name, c in (info.get("cells_by_type") or {}).items():
        mine[str(RAYINT_TYPES.get(name, name))] = c.get("read", 0)
    if not mine and info.get("tets") is not None:
        mine = {"10": info["tets"]}
    theirs = dict(o["cells"])  # both count ghost cells as read (rayint drops them afterwards)
    ghosts = o.get("ghost_cells", 0)
    vol = {"10", "11", "12", "13", "14", "24", "25"}
    for t in sorted(set(mine) | set(theirs)):
        if t in vol and mine.get(t, 0) != theirs.get(t, 0):
            notes.append("cells of VTK type %s: rayint %d, %s %d" % (t, mine.get(t, 0), o["reader"], theirs.get(t, 0)))
    if ghosts and info.get("ghost_cells") != ghosts:
        notes.append("ghost cells: rayint %s, %s %d" % (info.get("ghost_cells"), o["reader"], ghosts))
    sc = (info.get("scalar") or {}).get("name")
    if entry.get("field") and sc and sc != entry["field"] and not entry["file"].endswith(".ele"):  # TetGen: unnamed
        notes.append("scalar: rayint took %r, the file's field is %r" % (sc, entry["field"]))
    return notes


def worst_pair(rs):
    worst, pair = 0.0, None
    for r in rs[1:]:
        for a, b in zip(rs[0]["intensities"], r["intensities"]):
            for x, y in zip(a or [], b or []):
                d = abs(x - y) / max(abs(x), abs(y), 1e-300)
                if d > worst:
                    worst, pair = d, (rs[0]["file"], r["file"])
    return worst, pair


def family_spread(results, entries):
    """Per family (one mesh or image written by several tools or options): the largest relative
    difference of a ray's intensity from the family's first integrated file, over all its files and
    over the files whose data VTK/meshio read identically (same points and field, float64 digests).
    The second must be at rounding level: the same data integrated along the same rays."""
    by_family = collections.defaultdict(list)
    for e, r in zip(entries, results):
        if r.get("intensities") and r["outcome"].startswith("integrated"):
            o = e.get("oracle") or {}
            r["_digest"] = (o.get("points_digest"), o.get("field_digest")) if o.get("field_digest") else None
            by_family[e["family"]].append(r)
    spread = {}
    for fam, rs in by_family.items():
        if len(rs) < 2:
            continue
        worst, pair = worst_pair(rs)
        same = collections.defaultdict(list)
        for r in rs:
            if r["_digest"]:
                same[r["_digest"]].append(r)
        same_worst, same_pair, same_files = 0.0, None, 0
        for group in same.values():
            if len(group) >= 2:
                same_files += len(group)
                w, p = worst_pair(group)
                if w >= same_worst:
                    same_worst, same_pair = w, p
        spread[fam] = {"files": len(rs), "max_rel_diff": worst, "pair": pair, "same_data_files": same_files,
                       "same_data_max_rel_diff": same_worst if same_files else None, "same_data_pair": same_pair}
    for r in results:
        r.pop("_digest", None)
    return spread


# Different meshes of one domain carrying one linear field: every exact integral along the same rays
# is the same number whatever the tetrahedra (a linear field is interpolated exactly), so files made
# by different tools and read by different readers must agree to rounding. The gmsh box and the
# TetGen cube are [-1,1]^3 with s = 0.5 + 0.3x - 0.2y + 0.4z (make-corpus.sh).
LINEAR_GROUPS = {"cube [-1,1]^3, s linear": lambda fam: fam.startswith("gmsh-box-") or fam.startswith("tetgen-cube")}


def linear_groups(entries, results):
    out = {}
    for name, member in LINEAR_GROUPS.items():
        rs, off = [], []
        for e, r in zip(entries, results):
            if member(e["family"]) and r.get("intensities") and r["outcome"].startswith("integrated"):
                res = (e.get("oracle") or {}).get("linear_residual")
                (rs if res is not None and res < 1e-9 else off).append((r, res))
        if len(rs) >= 2:
            worst, pair = worst_pair([r for r, _ in rs])
            out[name] = {"files": len(rs), "max_rel_diff": worst, "pair": pair,
                         "not_linear": [(r["file"], res) for r, res in off]}
    return out


def summary(entries, results, spread, rayint):
    lines = []
    kinds = ["mesh", "image", "colormap"]
    lines.append("| kind | files | integrated / imported | of which cells in their own interpolation | refused (one line) | unclear / crash |")
    lines.append("|---|---|---|---|---|---|")
    for k in kinds:
        rs = [r for e, r in zip(entries, results) if e["kind"] == k]
        c = collections.Counter(r["outcome"] for r in rs)
        own = c["integrated (own interpolation)"]
        lines.append("| %s | %d | %d | %d | %d | %d |" % (k, len(rs), c["integrated"] + own + c["imported"],
                                                           own, c["refused"], c["unclear"]))
    for title, key in [("tool", "tool_short"), ("format", "format")]:
        lines.append("\n### Meshes and images by %s\n" % title)
        lines.append("| %s | files | integrated | of which own interpolation | refused | unclear |" % title)
        lines.append("|---|---|---|---|---|---|")
        groups = collections.OrderedDict()
        for e, r in zip(entries, results):
            if e["kind"] == "colormap":
                continue
            g = e["tool"].split(" (")[0] if key == "tool_short" else "%s: %s" % (e["kind"], e["format"])
            if key == "tool_short" and e["tool"].startswith("gmsh 4.8 .vtk export"):
                g = "gmsh 4.8 .vtk + appended field"
            groups.setdefault(g, collections.Counter())[r["outcome"]] += 1
        for g, c in sorted(groups.items()):
            own = c["integrated (own interpolation)"]
            lines.append("| %s | %d | %d | %d | %d | %d |" % (g, sum(c.values()), c["integrated"] + own,
                                                             own, c["refused"], c["unclear"]))
    lines.append("\n### Refusals, grouped (the line with the file's name and numbers taken out)\n")
    groups = collections.defaultdict(list)
    for e, r in zip(entries, results):
        if r["outcome"] == "refused":
            key = normalise(r["detail"], e)
            groups[(e["kind"], key)].append(e["file"])
    by_class = collections.Counter()
    for (kind, key), fs in groups.items():
        by_class[(kind, refusal_class(key))] += len(fs)
    lines.append("| kind | refused | why |")
    lines.append("|---|---|---|")
    for (kind, cls), n in sorted(by_class.items(), key=lambda kv: (kv[0][0], -kv[1])):
        lines.append("| %s | %d | %s |" % (kind, n, cls))
    lines.append("")
    lines.append("| kind | files | reason | class | e.g. |")
    lines.append("|---|---|---|---|---|")
    for (kind, key), fs in sorted(groups.items(), key=lambda kv: (kv[0][0], -len(kv[1]))):
        lines.append("| %s | %d | %s | %s | `%s` |" % (kind, len(fs), key.replace("|", "\\|"), refusal_class(key), fs[0]))
    lines.append("\n### Unclear outcomes (crashes, time-outs, several lines, suspicious answers)\n")
    unclear = [(e, r) for e, r in zip(entries, results) if r["outcome"] == "unclear"]
    lines += ["- `%s` (%s): %s" % (e["file"], r.get("stage"), r.get("detail")) for e, r in unclear] or ["none"]
    lines.append("\n### Cross-checks against VTK's / meshio's reading\n")
    mism = [(e, r) for e, r in zip(entries, results) if r.get("cross_check")]
    lines += ["- `%s`: %s" % (e["file"], "; ".join(r["cross_check"])) for e, r in mism] or [
        "every file rayint read has the cells by type (ghosts removed) and field VTK/meshio read"]
    nocheck = [e["file"] for e, r in zip(entries, results) if e["kind"] == "mesh" and r.get("info") and not e.get("oracle")]
    if nocheck:
        lines.append("- not cross-checked (the oracle reader could not read them): " + ", ".join("`%s`" % f for f in nocheck))
    lines.append("\n### Same data, many writers: largest relative difference of a ray's intensity within a family\n")
    lines.append("| family | files integrated | max rel. difference | between | files with data identical per VTK/meshio | max rel. difference among those |")
    lines.append("|---|---|---|---|---|---|")
    for fam, s in sorted(spread.items()):
        same = "%.2g" % s["same_data_max_rel_diff"] if s["same_data_max_rel_diff"] is not None else "-"
        if s["same_data_max_rel_diff"] and s["same_data_max_rel_diff"] > 1e-13:
            same += " **suspicious**"
        lines.append("| %s | %d | %.2g | %s | %d | %s |" % (fam, s["files"], s["max_rel_diff"],
                     " / ".join("`%s`" % os.path.basename(p) for p in s["pair"]) if s["pair"] else "", s["same_data_files"], same))
    lines.append("\n### One linear field on different meshes of one domain (any tetrahedra: the same exact integral)\n")
    lines.append("| domain and field | files integrated | max rel. difference | between |")
    lines.append("|---|---|---|---|")
    for name, g in linear_groups(entries, results).items():
        lines.append("| %s | %d | %.2g | %s |" % (name, g["files"], g["max_rel_diff"],
                                                 " / ".join("`%s`" % p for p in g["pair"]) if g["pair"] else ""))
        if g["not_linear"]:
            lines.append("")
        for f, res in g["not_linear"]:
            lines.append("- left out: `%s`: its field (as VTK/meshio read it) is %s from the linear s" % (
                f, "%.3g" % res if res is not None else "not known (no oracle reading)"))
    cms = [r for e, r in zip(entries, results) if e["kind"] == "colormap" and r["outcome"] == "imported"]
    if cms:
        worst = max(cms, key=lambda r: r.get("max_deviation") or 0)
        lines.append("\nColour maps imported: %d; worst linearisation deviation stated by the import report %.3g (%s)" % (
            len(cms), worst.get("max_deviation") or 0, worst["name"]))
    return "\n".join(lines)


REFUSAL_CLASSES = [  # (words in the line, class): whether refusing is right or a gap, for the summary
    (("no field", "no one-component", "no point attributes"), "right: the file holds no field (markers only)"),
    (("overlap", "shared by more than two"), "right: overlapping or repeated cells (a ray would count the volume twice)"),
    (("no volume cells", "CELLS: missing", "has no cells"), "right: the file holds no cells (an empty output)"),
    (("categorical",), "right: a categorical map has no continuous transfer function"),
    (("not in $Nodes", "out of range [N, N]"), "the file contradicts itself (gmsh: $NodeData for a node not in $Nodes)"),
    (("not supported", "Direction is not the identity", "cell data only", "not a VTK cell type"),
     "gap: not supported yet"),
    (("with a curved edge",), "gap: curved quadratic tetrahedra (isoparametric cells: not integrated yet)"),
    (("all nodes coincide",), "gap: a degenerate cell (all nodes at one point) refused by the own interpolation"),
]


def refusal_class(reason):
    for words, cls in REFUSAL_CLASSES:
        if any(w in reason for w in words):
            return cls
    return "other"


def normalise(line, entry):
    import re
    s = line[len("rayint: error: "):] if line.startswith("rayint: error: ") else line
    stem = os.path.splitext(entry["file"])[0]
    for name in (entry["file"], stem + ".node"):  # the path as given, or a TetGen .ele's .node
        i = s.find(name)
        if i >= 0:
            s = "FILE" + s[i + len(name):]
            break
    s = re.sub(r'"[^"]*"', '"…"', s)
    s = re.sub(r"\b\d+(\.\d+)?(e[-+]?\d+)?\b", "N", s)
    return s[:220]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("rayint")
    ap.add_argument("corpus")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("-o", "--output")
    ap.add_argument("--fail-on-unclear", action="store_true", help="exit 1 if any file's outcome is unclear (a crash, ...)")
    args = ap.parse_args()
    rayint = os.path.abspath(args.rayint)
    corpus = os.path.abspath(args.corpus)
    manifest = json.load(open(os.path.join(corpus, "manifest.json")))
    entries = manifest["files"]
    fn = {"mesh": count_mesh, "image": count_image, "colormap": count_colormap}

    def one(entry):
        with tempfile.TemporaryDirectory() as tmp:
            r = fn[entry["kind"]](rayint, corpus, entry, tmp, args.timeout)
        r["cross_check"] = cross_check(entry, r) if entry["kind"] == "mesh" else []
        return r

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        results = list(pool.map(one, entries))
    spread = family_spread(results, entries)
    version = run([rayint, "--version"], 10)[1].strip()
    if args.output:
        with open(args.output, "w") as f:
            json.dump({"rayint": version, "corpus": corpus, "tools": manifest.get("tools"), "family_spread": spread,
                       "results": [dict(r, kind=e["kind"], tool=e["tool"], format=e["format"], family=e["family"],
                                        how=e["how"]) for e, r in zip(entries, results)]}, f, indent=1)
    print("## rayint on the real-files corpus (%s, %s)\n" % (version, corpus))
    print(summary(entries, results, spread, rayint))
    unclear = sum(1 for r in results if r["outcome"] == "unclear")
    if args.fail_on_unclear and unclear:
        print("count.py: %d unclear outcomes (listed above)" % unclear, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
