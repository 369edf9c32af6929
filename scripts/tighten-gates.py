#!/usr/bin/python3
"""Sets every accuracy limit of a gate config to 1.5x what the gate measured (rounded up to two
significant digits), so each limit sits within 2x of the measured error.

    build/rayint gate --config cases/gates.json --json -o /tmp/gate.json --quiet
    /usr/bin/python3 scripts/tighten-gates.py cases/gates.json /tmp/gate.json > new.json

Per limit set, the measured value is the largest over the cases (or stress regimes) the set applies
to; max_non_finite limits are left as they are; a measured 0 keeps a limit of 0."""
import json, math, sys
from collections import OrderedDict

def nice_up(x):
    if x <= 0 or not math.isfinite(x):
        return x
    e = math.floor(math.log10(x)) - 1
    m = math.ceil(x / 10 ** e - 1e-9)
    return float(f"{m}e{e}")

config = json.load(open(sys.argv[1]), object_pairs_hook=OrderedDict)
report = json.load(open(sys.argv[2]))
measured = {}  # (part, method, metric) -> {case_or_regime: value}
for c in report["checks"]:
    parts = c["name"].split(".")
    if parts[0] not in ("corpus", "stress") or len(parts) < 4:
        continue
    part, where, metric = parts[0], parts[1], parts[-1]
    method = ".".join(parts[2:-1])
    if c["measured"] is None:
        continue
    measured.setdefault((part, method, metric), {})[where] = c["measured"]

for part in ("corpus", "stress"):
    if part not in config:
        continue
    for method, sets in config[part]["methods"].items():
        for s in (sets if isinstance(sets, list) else [sets]):
            scope = s.get("cases") or s.get("regimes")
            for metric in list(s.keys()):
                if metric in ("cases", "regimes", "max_non_finite"):
                    continue
                values = measured.get((part, method, metric), {})
                vals = [v for k, v in values.items() if scope is None or k in scope]
                if not vals:
                    continue
                m = max(vals)
                new = nice_up(1.5 * m) if m > 0 else 0.0
                print(f"{part} {method} {metric} {scope and len(scope)}: measured {m:.3g}, limit {s[metric]} -> {new}", file=sys.stderr)
                s[metric] = new

def dump(x, indent=0):
    """JSON with objects of scalars and arrays of scalars on one line, as cases/gates.json is laid out."""
    pad = "  " * indent
    simple = lambda v: not isinstance(v, (dict, list)) or (isinstance(v, list) and all(not isinstance(e, (dict, list)) for e in v))
    if isinstance(x, dict):
        if all(simple(v) for v in x.values()) and indent > 2:
            return "{" + ", ".join(json.dumps(k) + ": " + json.dumps(v) for k, v in x.items()) + "}"
        items = [pad + "  " + json.dumps(k) + ": " + dump(v, indent + 1) for k, v in x.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(x, list) and not simple(x):
        return "[\n" + ",\n".join(pad + "  " + dump(v, indent + 1) for v in x) + "\n" + pad + "]"
    return json.dumps(x)

print(dump(config))
