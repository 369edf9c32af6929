#!/usr/bin/python3
"""The corpus's meshes of quadratic cells in their own interpolation (reports/cells/quadratic.md).

  scripts/cells/quadratic_corpus.py RAYINT RESULTS_JSON CORPUS_DIR

RESULTS_JSON is count.py's per-file output (scripts/real-files/count.sh RAYINT CORPUS_DIR -o
RESULTS_JSON). For every mesh whose cells include quadratic tetra/hexahedron/wedge: `rayint eval`
(own mode, its default method and its per-ray 50-digit reference) on count.py's rays and transfer
function; prints one line per file: accepted (mode, cells, failed rays, largest absolute and
relative error against the reference) or the refusal."""
import json
import os
import subprocess
import sys
import tempfile

rayint, results, corpus = sys.argv[1], sys.argv[2], sys.argv[3]
for r in json.load(open(results))["results"]:
    cells = (r.get("info") or {}).get("cells_by_type") or {}
    if not any(k in cells for k in ("quadratic tetra", "quadratic hexahedron", "quadratic wedge")):
        continue
    if "rays" not in r:
        print("%s | refused before eval | %s" % (r["file"], r.get("detail", "")[:160]))
        continue
    d = tempfile.mkdtemp()
    case = {"name": "q", "mesh_file": os.path.join(corpus, r["file"]), "background": [0, 0, 0], "rays": r["rays"],
            "transfer_function": r["tf"]}
    json.dump(case, open(d + "/c.json", "w"))
    p = subprocess.run([rayint, "eval", d + "/c.json", "--no-timing", "-q", "-o", d + "/o.json"], capture_output=True,
                       text=True, timeout=900)
    if p.returncode != 0:
        print("%s | exit %d | %s" % (r["file"], p.returncode, p.stderr.strip()[:160]))
        continue
    c = json.load(open(d + "/o.json"))["cases"][0]
    rel = max(abs(x["abs_error"]) / max(1e-300, max(abs(v) for v in x["intensity"])) for x in c["rays"])
    print("%s | mode %s, %s, failed %d, max |err| %.2e, max rel %.2e" %
          (r["file"], c.get("mode"), json.dumps(c.get("cells")), c["failed"], c["max_abs_error"], rel))
