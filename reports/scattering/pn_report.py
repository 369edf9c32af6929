#!/usr/bin/python3
"""P_N for the plane-parallel slab against the doubling and the published DISORT values.

Makes reports/scattering/pn.json, pn.md (tables), pn_convergence.png and pn_p1_diffusion.png,
all from `rayint slab` runs (--method pn:order=N[:bc=mark] and --method doubling) and, for the
cost, the Google Benchmark BM_slab_pn / BM_slab_doubling (bench/bench_slab_pn.cpp).

Usage: /usr/bin/python3 reports/scattering/pn_report.py [BUILD_DIR]   (default build/)
"""
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from report_env import BUILD, ROOT, p1_map, plot_p1_map, plt, slab  # noqa: E402

BENCH = os.path.join(BUILD, "bench", "rayint_bench")
OUT = os.path.join(ROOT, "reports", "scattering")
ORDERS = [1, 3, 5, 7, 15, 31, 63, 127]
BENCH_REPEATS = 5


def problem_args(p, phase):
    a = ["--tau", repr(p["tau"]), "--albedo", repr(p["albedo"]), "--phase", phase]
    if p["source"] == "beam":
        a += ["--source", "beam", "--mu0", repr(p["mu0"])]
    else:
        a += ["--source", "isotropic"]
    up = sorted(float(m) for m in p.get("intensity_up_top", {}))
    down = sorted(float(m) for m in p.get("intensity_down_bottom", {}))
    up = up or [0.1, 0.5, 1.0]
    down = down or [0.1, 0.5, 1.0]
    a += ["--mu-up", ",".join(map(repr, up)), "--mu-down", ",".join(map(repr, down))]
    return a, up, down


def values(res, up, down):
    """(label, value) of the fluxes and intensities of one method's result."""
    out = [("flux_up_top", res["flux_up_top"]), ("diffuse_down_bottom", res["diffuse_down_bottom"])]
    out += [(f"intensity_up_top({m:g})", v) for m, v in zip(up, res["intensity_up_top"])]
    out += [(f"intensity_down_bottom({m:g})", v) for m, v in zip(down, res["intensity_down_bottom"])]
    return out


def published(p):
    out = {}
    for q in ("flux_up_top", "diffuse_down_bottom"):
        if q in p:
            out[q] = p[q]
    for q in ("intensity_up_top", "intensity_down_bottom"):
        for m, v in p.get(q, {}).items():
            out[f"{q}({float(m):g})"] = v
    return out


def rel(a, b):
    return abs(a - b) / abs(b)


def convergence():
    bench = json.load(open(os.path.join(ROOT, "cases", "scattering", "disort_slab.json")))
    rows = []
    for group, phase in (("isotropic", "isotropic"), ("henyey_greenstein_g0.75", "hg:0.75")):
        for p in bench[group]:
            args, up, down = problem_args(p, phase)
            ref = dict(values(slab(args, "doubling")["doubling"], up, down))
            pub = published(p)
            row = {"id": p["id"], "tau": p["tau"], "albedo": p["albedo"], "phase": phase,
                   "source": p["source"], "doubling_vs_published": max(rel(ref[k], v) for k, v in pub.items()),
                   "orders": {}}
            for bc in ("marshak", "mark"):
                for n in ORDERS:
                    r = slab(args, f"pn:order={n}:bc={bc}")["pn"]
                    v = dict(values(r, up, down))
                    series = dict(values(dict(r, intensity_up_top=r["series_intensity_up_top"],
                                              intensity_down_bottom=r["series_intensity_down_bottom"]), up, down))
                    inten = [k for k in v if k.startswith("intensity")]
                    flux = [k for k in v if k.startswith(("flux", "diffuse"))]
                    row["orders"][f"{bc}:{n}"] = {
                        "intensity_vs_doubling": max(rel(v[k], ref[k]) for k in inten),
                        "series_intensity_vs_doubling": max(rel(series[k], ref[k]) for k in inten),
                        "flux_vs_doubling": max(rel(v[k], ref[k]) for k in flux),
                        "vs_published": max(rel(v[k], x) for k, x in pub.items()),
                        "seconds_one_solve": r["seconds"],
                    }
            rows.append(row)
            print("pn_report:", p["id"], file=sys.stderr)
    return rows


def order_fit(errors):
    """Least-squares slope of -log(error) against log N over N = 15..127."""
    pts = [(math.log(n), math.log(e)) for n, e in errors if n >= 15 and e > 0]
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return -sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def cost():
    if not os.path.exists(BENCH):
        return None
    r = subprocess.run([BENCH, "--benchmark_filter=BM_slab_", f"--benchmark_repetitions={BENCH_REPEATS}",
                        "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                       check=True, capture_output=True, text=True)
    out = {}
    for b in json.loads(r.stdout)["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        scale = {"us": 1e-6, "ms": 1e-3, "ns": 1e-9}[b["time_unit"]]
        out[b["run_name"] + ":" + b.get("label", "")] = b["real_time"] * scale
    return out


def beam_p1_map():
    """P1 (diffusion with Marshak's boundary) against the doubling over albedo and thickness."""
    return p1_map(["--mu0", "1"], (1, 3, 7),
                  lambda p, d: {"reflectance": rel(p["flux_up_top"], d["flux_up_top"]),
                                "transmittance": rel(p["diffuse_down_bottom"] + p["direct_down_bottom"],
                                                     d["diffuse_down_bottom"] + d["direct_down_bottom"]),
                                "I_up(1)": rel(p["intensity_up_top"][0], d["intensity_up_top"][0])},
                  after=lambda d: {"doubling_reflectance": d["flux_up_top"] / math.pi},
                  progress="pn_report: P1 map")


def fmt(x):
    return f"{x:.1e}"


def write(rows, costs, p1):
    json.dump({"convergence": rows, "cost_seconds_median": costs, "p1": p1, "orders": ORDERS,
               "bench_repetitions": BENCH_REPEATS}, open(os.path.join(OUT, "pn.json"), "w"), indent=1)
    L = ["<!-- generated by reports/scattering/pn_report.py; do not edit -->", ""]
    for what, title in (("intensity_vs_doubling", "intensities (source-function integration) vs doubling"),
                        ("series_intensity_vs_doubling", "intensities from the truncated series vs doubling"),
                        ("flux_vs_doubling", "fluxes (from the moments) vs doubling"),
                        ("vs_published", "every published value vs DISORT/van de Hulst")):
        for bc in ("marshak", "mark"):
            L.append(f"**Largest relative error, {title}, {bc.capitalize()} boundary conditions**")
            L.append("")
            head = "| problem | " + " | ".join(f"P{n}" for n in ORDERS) + " | order (N ≥ 15) |"
            if what == "vs_published":
                head = head + " doubling vs published |"
            L.append(head)
            L.append("|" + "---|" * (head.count("|") - 1))
            for r in rows:
                e = [r["orders"][f"{bc}:{n}"][what] for n in ORDERS]
                cells = " | ".join(fmt(x) for x in e)
                line = (f"| {r['id']} (τ {r['tau']:g}, ω {r['albedo']:g}, {r['phase']}, {r['source']}) | {cells} | "
                        f"{order_fit(list(zip(ORDERS, e))):.2f} |")
                if what == "vs_published":
                    line += f" {fmt(r['doubling_vs_published'])} |"
                L.append(line)
            L.append("")
    if costs:
        L.append(f"**Cost per solve** (Google Benchmark `BM_slab_pn`, median of {BENCH_REPEATS} repetitions; "
                 "3 + 3 detector cosines; wall time on the shared 2-core machine)")
        L.append("")
        L.append("| problem | " + " | ".join(f"P{n}" for n in (1, 3, 7, 15, 31, 63, 127)) + " | doubling (64 streams) |")
        L.append("|---|" + "---:|" * 8)
        for pid in ("1e", "3a"):
            cells = []
            for n in (1, 3, 7, 15, 31, 63, 127):
                k = next((k for k in costs if k.startswith(f"BM_slab_pn/{0 if pid == '1e' else 1}/{n}:")), None)
                cells.append(f"{costs[k] * 1e6:.0f} µs" if k else "-")
            k = next((k for k in costs if k.startswith(f"BM_slab_doubling/{0 if pid == '1e' else 1}:")), None)
            cells.append(f"{costs[k] * 1e3:.1f} ms" if k else "-")
            L.append(f"| {pid} | " + " | ".join(cells) + " |")
        L.append("")
    open(os.path.join(OUT, "pn_tables.md"), "w").write("\n".join(L) + "\n")


def figures(rows, costs, p1):
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, r in enumerate(rows):
        c = colors[i % len(colors)]
        e = [r["orders"][f"marshak:{n}"]["intensity_vs_doubling"] for n in ORDERS]
        s = [r["orders"][f"marshak:{n}"]["series_intensity_vs_doubling"] for n in ORDERS]
        f = [r["orders"][f"marshak:{n}"]["flux_vs_doubling"] for n in ORDERS]
        ax[0].loglog(ORDERS, e, "o-", color=c, label=r["id"])
        ax[0].loglog(ORDERS, s, ":", color=c)
        ax[1].loglog(ORDERS, f, "s-", color=c, label=r["id"])
    ref = [0.3 * (n / 1.0) ** -2 for n in ORDERS]
    for a in ax[:2]:
        a.loglog(ORDERS, ref, "k--", lw=0.8, label="N^-2")
        a.set_xlabel("order N")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7, ncol=2)
    ax[0].set_ylabel("largest relative error vs doubling")
    ax[0].set_title("intensities: source-function integration (—), series (···)")
    ax[1].set_title("fluxes from the moments")
    if costs:
        for pid, m in (("1e", 0), ("3a", 1)):
            ns, ts = [], []
            for n in (1, 3, 7, 15, 31, 63, 127):
                k = next((k for k in costs if k.startswith(f"BM_slab_pn/{m}/{n}:")), None)
                if k:
                    ns.append(n)
                    ts.append(costs[k])
            ax[2].loglog(ns, ts, "o-", label=f"P_N, {pid}")
            k = next((k for k in costs if k.startswith(f"BM_slab_doubling/{m}:")), None)
            if k:
                ax[2].axhline(costs[k], ls="--", color=ax[2].lines[-1].get_color(), label=f"doubling 64 streams, {pid}")
        ax[2].set_xlabel("order N")
        ax[2].set_ylabel("seconds per solve (median)")
        ax[2].set_title("cost")
        ax[2].grid(True, which="both", alpha=0.3)
        ax[2].legend(fontsize=7)
    fig.suptitle("P_N (Marshak) on the DISORT slab problems against the adding-doubling reference")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "pn_convergence.png"), dpi=110)

    plot_p1_map(p1, "beam μ0 = 1",
                "The diffusion approximation (P1, Marshak boundary) across albedo and thickness; dotted: P3",
                os.path.join(OUT, "pn_p1_diffusion.png"))


def main():
    rows = convergence()
    costs = cost()
    p1 = beam_p1_map()
    write(rows, costs, p1)
    figures(rows, costs, p1)


if __name__ == "__main__":
    main()
