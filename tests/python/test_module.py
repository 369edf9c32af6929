"""The Python module against the CLI (bit for bit), against the 50-digit reference, its errors,
and the NeRF quadratures on explicit samples against an independent NumPy transcription.

Run by CTest (test `python_module`) as `/usr/bin/python3 -m pytest tests/python` with
PYTHONPATH=<build>/python, RAYINT_CLI=<build>/rayint and RAYINT_SOURCE_DIR set.
"""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import rayint

SOURCE = os.environ.get("RAYINT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("RAYINT_CLI", os.path.join(SOURCE, "build", "rayint"))
CASES = os.path.join(SOURCE, "cases")
# Issue 2's target for `exact` against the 50-digit reference (tests/tolerances.hpp exact_rel).
EXACT_REL = 1e-13


def cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True)


def rel_error(got, ref):
    if ref == 0.0:
        return 0.0 if got == 0.0 else math.inf
    return abs(got - ref) / abs(ref)


def piece_case(rho_exit, rho_far, kappa_exit, kappa_far, length):
    """One linear piece as a case: scalar 1 at the exit end, 0 at the far end, the transfer
    functions linear between the given end values (the same colour for r, g, b)."""
    return {"name": "piece",
            "transfer_function": {"density": [[0.0, rho_far], [1.0, rho_exit]],
                                  "color": [[0.0, kappa_far], [1.0, kappa_exit]]},
            "rays": [{"segments": [{"length": length, "scalar": [0.0, 1.0]}]}]}


# Pieces across the regimes of exact.cpp (thin series, q2 series, erfcx, dawson, transparent,
# zero at one end, huge kappa with tiny rho, thick).
PIECES = [(0.0, 0.0, 1.0, 2.0, 1.0), (1e-9, 3e-9, 1.0, 1.0, 2.0), (0.3, 0.5, 0.2, 0.9, 1.0),
          (2.0, 2.0 + 1e-9, 0.7, 0.1, 3.0), (5.0, 1.0, 1.3, 0.4, 1.0), (1.0, 6.0, 0.4, 1.3, 1.0),
          (0.0, 4.0, 1.0, 0.0, 2.0), (3.0, 0.0, 0.5, 0.5, 1.5), (1e-12, 2e-12, 1e9, 1e9, 1.0),
          (40.0, 70.0, 0.8, 0.3, 1.0), (0.02, 900.0, 1.0, 2.0, 0.5), (1e3, 1e3, 1.0, 1.0, 2.0)]


def test_import_and_methods():
    names = rayint.method_names()
    for m in ("exact", "paper", "riemann", "nerf", "pl_nerf"):
        assert m in names


@pytest.mark.parametrize("case", ["paper-figure-2.json", "narrow-pulse.json",
                                  "per-channel-densities.json", "scalar-outside-range.json",
                                  "mesh-inline-cube.json"])
def test_evaluate_is_the_cli_bit_for_bit(case):
    methods = "exact,paper,riemann:n=16,nerf:n=8,nerf:n=8:at=near:last=inf,pl_nerf:n=8"
    path = os.path.join(CASES, case)
    r = cli("eval", path, "--methods", methods, "--no-timing")
    assert r.returncode == 0, r.stderr
    assert rayint.evaluate(path, methods=methods.split(","), timing=False) == json.loads(r.stdout)


def test_evaluate_takes_a_dict_and_a_folder(tmp_path):
    path = os.path.join(CASES, "paper-figure-2.json")
    with open(path) as f:
        doc = json.load(f)
    from_dict = rayint.evaluate(doc, methods="exact", timing=False)
    from_path = rayint.evaluate(path, methods="exact", timing=False)
    assert from_dict["cases"][0]["rays"] == from_path["cases"][0]["rays"]
    assert from_dict["cases"][0]["name"] == "paper-figure-2"
    assert from_dict["cases"][0]["file"] == "<case dict>"
    for name in ("paper-figure-2.json", "narrow-pulse.json"):
        with open(os.path.join(CASES, name)) as src:
            (tmp_path / name).write_text(src.read())
    folder = rayint.evaluate(str(tmp_path), methods="exact", timing=False)
    assert [c["name"] for c in folder["cases"]] == ["narrow-pulse", "paper-figure-2"]


def test_exact_pieces_against_the_reference_and_the_exact_method():
    cols = [np.array(c, dtype=np.float64) for c in zip(*PIECES)]
    emission, transmittance = rayint.exact_pieces(*cols)
    for i, p in enumerate(PIECES):
        case = piece_case(*p)
        ref = rayint.reference(case)["rays"][0]
        assert rel_error(emission[i], ref["intensity"][0]) <= EXACT_REL, p
        assert rel_error(transmittance[i], ref["transmittance"][0]) <= EXACT_REL, p
        # The same C++ path as the `exact` method (black background: intensity = emission).
        intensity, trans = rayint.integrate("exact", case)
        assert intensity[0, 0] == emission[i] and trans[0, 0] == transmittance[i], p


def test_exact_pieces_broadcasts():
    e, t = rayint.exact_pieces(np.linspace(0.0, 3.0, 4)[:, None], 1.0, 0.5, [0.1, 0.2, 0.3], 2.0)
    assert e.shape == (4, 3) and t.shape == (4, 3) and e.dtype == np.float64
    e1, t1 = rayint.exact_pieces(2.0, 1.0, 0.5, 0.2, 2.0)
    assert e1.shape == () and e1 == e[2, 1] and t1 == t[2, 1]


def test_exact_pieces_bad_input_names_the_field():
    with pytest.raises(rayint.InputError) as err:
        rayint.exact_pieces([1.0, -1.0], 1.0, 1.0, 1.0, 1.0)
    assert str(err.value) == "exact_pieces: rho_exit[1]: must be finite and >= 0, got -1"
    with pytest.raises(ValueError):  # InputError is a ValueError
        rayint.exact_pieces(1.0, 1.0, 1.0, 1.0, np.nan)


def test_input_errors_carry_the_cli_message(tmp_path):
    bad = tmp_path / "bad.json"
    doc = piece_case(1.0, 2.0, 0.5, 0.5, 1.0)
    doc["rays"][0]["segments"][0]["length"] = -1
    bad.write_text(json.dumps(doc))
    r = cli("eval", str(bad))
    assert r.returncode == 2
    with pytest.raises(rayint.InputError) as err:
        rayint.evaluate(str(bad))
    assert r.stderr.strip() == "rayint: error: " + str(err.value)
    assert str(err.value).startswith(str(bad) + ": rays[0].segments[0].length: ")
    with pytest.raises(ValueError, match="unknown method 'nope'"):
        rayint.evaluate(os.path.join(CASES, "paper-figure-2.json"), methods=["nope"])


def test_check_is_the_cli_bit_for_bit(tmp_path):
    path = os.path.join(CASES, "paper-figure-2.json")
    exact = rayint.evaluate(path, methods="exact", timing=False)["cases"][0]
    rays = [{"intensity": ray["methods"]["exact"]["intensity"]} for ray in exact["rays"]]
    rays[1]["intensity"] = [x * (1 + 1e-5) for x in rays[1]["intensity"]]  # one ray fails
    candidate = {"case": "paper-figure-2", "renderer": "test", "rays": rays}
    cand_file = tmp_path / "cand.json"
    cand_file.write_text(json.dumps(candidate))
    r = cli("check", path, "--candidate", str(cand_file), "--rel-tol", "1e-6")
    assert r.returncode == 1
    diff = rayint.check(path, str(cand_file), rel_tol=1e-6)
    assert diff == json.loads(r.stdout)
    assert diff["pass"] is False
    assert rayint.check(path, candidate, rel_tol=1e-4)["pass"] is True
    with pytest.raises(rayint.InputError, match="cand.json"):
        bad = dict(candidate, rays=rays[:1])
        cand_file.write_text(json.dumps(bad))
        rayint.check(path, str(cand_file))


def twisted_case(tmp_path):
    """The twisted VTK grid (24 hexahedra, tests/fixtures/readers/cells-twisted.vts) with two rays,
    as a case file in tmp_path: cells other than tetrahedra, integrated in their own interpolation."""
    doc = {"name": "twisted",
           "transfer_function": {"density": [[0.2, 0.5], [0.45, 4.0], [0.7, 1.0]],
                                 "color": [[0.2, 1.0], [0.5, 0.1], [0.7, 0.8]]},
           "mesh_file": os.path.join(SOURCE, "tests", "fixtures", "readers", "cells-twisted.vts"),
           "rays": [{"origin": [0.05, 0.02, -1], "direction": [0.1, 0.05, 1]},
                    {"origin": [-0.3, 0.1, -1], "direction": [0.2, -0.1, 1]}]}
    path = tmp_path / "twisted.json"
    path.write_text(json.dumps(doc))
    return str(path), doc


def test_evaluate_and_check_take_cells_in_their_own_interpolation(tmp_path):
    path, doc = twisted_case(tmp_path)
    r = cli("eval", path, "--quiet")
    assert r.returncode == 0, r.stderr
    by_cli = json.loads(r.stdout)["cases"][0]
    own = rayint.evaluate(path)["cases"][0]
    assert own["mode"] == "own" and by_cli["mode"] == "own"
    assert own["rays"] == by_cli["rays"]  # bit for bit (the reference included)
    assert rayint.evaluate(doc)["cases"][0]["rays"] == own["rays"]
    # A candidate made of the 50-digit own-interpolation reference passes; one ray 1e-3 off fails,
    # and the diff is the CLI's.
    rays = [{"intensity": ray["reference"]} for ray in own["rays"]]
    candidate = {"case": "twisted", "renderer": "test", "rays": rays}
    assert rayint.check(path, candidate, rel_tol=1e-12)["pass"] is True
    rays[1]["intensity"] = [x * (1 + 1e-3) for x in rays[1]["intensity"]]
    cand_file = tmp_path / "cand.json"
    cand_file.write_text(json.dumps(candidate))
    r = cli("check", path, "--candidate", str(cand_file), "--rel-tol", "1e-6", "--quiet")
    assert r.returncode == 1, r.stderr
    diff = rayint.check(path, str(cand_file), rel_tol=1e-6)
    assert diff == json.loads(r.stdout)
    assert diff["pass"] is False and diff["summary"]["failed_rays"] == 1
    with pytest.raises(rayint.InputError, match="cand.json: rays: has 1 entries"):
        cand_file.write_text(json.dumps(dict(candidate, rays=rays[:1])))
        rayint.check(path, str(cand_file))


def test_cells_split_is_the_cli_split(tmp_path):
    path, _ = twisted_case(tmp_path)
    r = cli("eval", path, "--cells", "split", "--methods", "exact", "--no-timing", "--quiet")
    assert r.returncode == 0, r.stderr
    split = rayint.evaluate(path, methods="exact", timing=False, cells="split")
    assert split == json.loads(r.stdout)
    ref = rayint.reference(path, cells="split")["rays"]
    assert [x["intensity"] for x in ref] == [x["reference"]["intensity"] for x in split["cases"][0]["rays"]]


def test_own_cells_refusals(tmp_path):
    path, _ = twisted_case(tmp_path)
    with pytest.raises(rayint.InputError, match="twisted.json: mesh_file: .*comes with evaluate"):
        rayint.reference(path)
    with pytest.raises(rayint.InputError, match="twisted.json: methods: the own interpolation"):
        rayint.evaluate(path, methods="exact")
    with pytest.raises(rayint.InputError, match="cannot be evaluated together with segment cases"):
        rayint.evaluate([path, os.path.join(CASES, "paper-figure-2.json")])
    with pytest.raises(ValueError, match="cells must be 'own' or 'split'"):
        rayint.evaluate(path, cells="tets")


def test_integrate_on_arrays_matches_the_case():
    path = os.path.join(CASES, "paper-figure-2.json")
    with open(path) as f:
        doc = json.load(f)
    ray = doc["rays"][0]
    length = [s["length"] for s in ray["segments"]]
    far = [s["scalar"][0] for s in ray["segments"]]
    exit_ = [s["scalar"][1] for s in ray["segments"]]
    for method in ("exact", "nerf:n=32", "pl_nerf:n=32"):
        i_case, t_case = rayint.integrate(method, path)
        i_arr, t_arr = rayint.integrate(method, path, length, far, exit_, ray.get("background"))
        assert i_arr.shape == (1, 3)
        assert (i_arr[0] == i_case[0]).all() and (t_arr[0] == t_case[0]).all()


def numpy_nerf(sigma, rgb, delta):
    """NeRF 2020 Eq. 3 transcribed in NumPy (independent of the C++ code)."""
    alpha = 1.0 - np.exp(-sigma * delta)
    trans = np.cumprod(np.concatenate([np.ones_like(alpha[..., :1]), 1.0 - alpha], -1), -1)
    return (trans[..., :-1, None] * alpha[..., None] * rgb).sum(-2), trans[..., -1]


def numpy_pl_nerf(sigma, rgb, t):
    """PL-NeRF's piecewise-linear sum transcribed in NumPy (independent of the C++ code)."""
    tau = 0.5 * (sigma[..., 1:] + sigma[..., :-1]) * np.diff(t, axis=-1)
    alpha = 1.0 - np.exp(-tau)
    trans = np.cumprod(np.concatenate([np.ones_like(alpha[..., :1]), np.exp(-tau)], -1), -1)
    colour = 0.5 * (rgb[..., 1:, :] + rgb[..., :-1, :])
    return (trans[..., :-1, None] * alpha[..., None] * colour).sum(-2), trans[..., -1]


def test_nerf_composites_against_numpy():
    rng = np.random.default_rng(5)
    t = np.sort(rng.uniform(2.0, 6.0, (7, 40)), axis=-1)
    sigma = rng.uniform(0.0, 5.0, (7, 40))
    rgb = rng.uniform(0.0, 1.0, (7, 40, 3))
    delta = rayint.nerf_deltas(t)
    got, trans = rayint.nerf_composite(sigma, rgb, delta)
    want, want_t = numpy_nerf(sigma, rgb, delta)
    assert np.allclose(got, want, rtol=1e-13, atol=0) and np.allclose(trans[:, 0], want_t, rtol=1e-12, atol=1e-300)
    got, trans = rayint.pl_nerf_composite(sigma, rgb, t)
    want, want_t = numpy_pl_nerf(sigma, rgb, t)
    assert np.allclose(got, want, rtol=1e-13, atol=0) and np.allclose(trans[:, 0], want_t, rtol=1e-13, atol=0)


def test_nerf_composite_is_the_nerf_method():
    # One segment with the scalar running from 0.9 (far) to 0.1 (exit); the method's own midpoint
    # samples handed over explicitly must give its number.
    doc = {"name": "one", "transfer_function": {"density": [[0.0, 0.5], [1.0, 3.0]],
                                                 "color": [[0.0, 1.0], [1.0, 0.2]]},
           "rays": [{"segments": [{"length": 2.0, "scalar": [0.9, 0.1]}]}]}
    n = 16
    s = 0.1 + ((np.arange(n) + 0.5) / n) * (0.9 - 0.1)
    sigma = 0.5 + 2.5 * s
    colour = 1.0 - 0.8 * s
    rgb = np.repeat(colour[:, None], 3, axis=1)
    got, _ = rayint.nerf_composite(sigma, rgb, np.full(n, 2.0 / n))
    method, _ = rayint.integrate(f"nerf:n={n}", doc)
    assert np.allclose(got, method[0], rtol=1e-13, atol=0)


def test_example_script_exact_against_the_reference():
    # The example's "exact" is the integral of the piecewise-linear interpolant of the samples.
    # The same integral as a case (transfer functions through the samples, scalar = t) goes to the
    # independent 50-digit reference.
    script = os.path.join(SOURCE, "scripts", "examples", "nerf_quadrature_error.py")
    sample = os.path.join(SOURCE, "scripts", "examples", "nerf_sample.npz")
    r = subprocess.run([sys.executable, script, sample, "--json"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    report = json.loads(r.stdout)
    data = np.load(sample)
    t, sigma, rgb, bg = data["t"], data["sigma"], data["rgb"], data["background"]
    for ray in (0, 5, 11):
        tf = {"density": [[float(a), float(b)] for a, b in zip(t[ray], sigma[ray])],
              "color": {ch: [[float(a), float(b)] for a, b in zip(t[ray], rgb[ray, :, k])]
                        for k, ch in enumerate("rgb")}}
        case = {"name": "samples", "transfer_function": tf,
                "rays": [{"background": bg.tolist(),
                          "segments": [{"length": float(t[ray, -1] - t[ray, 0]),
                                        "scalar": [float(t[ray, -1]), float(t[ray, 0])]}]}]}
        ref = rayint.reference(case)["rays"][0]
        for k in range(3):
            assert rel_error(report["exact"][ray][k], ref["intensity"][k]) <= EXACT_REL
        # The quadratures it reports are NeRF's and PL-NeRF's sums (independent NumPy versions).
        nerf, nerf_t = numpy_nerf(sigma[ray], rgb[ray], np.append(np.diff(t[ray]), 0.0))
        assert np.allclose(report["values"]["nerf"][ray], nerf + nerf_t * bg, rtol=1e-13, atol=0)
        pl, pl_t = numpy_pl_nerf(sigma[ray], rgb[ray], t[ray])
        assert np.allclose(report["values"]["pl_nerf"][ray], pl + pl_t * bg, rtol=1e-13, atol=0)
    for name, e in report["errors"].items():
        assert all(math.isfinite(v) for v in e.values()), name


# Issue 26: a method spec is checked against the method table before anything runs (InputError,
# the CLI's line), and a method that fails on a ray is reported as failed, never as a number.
INVALID_SPECS = [
    ("riemann:n=0", "riemann:n=0: n must be an integer >= 1"),
    ("nerf:n=0", "nerf:n=0: n must be an integer >= 1"),
    ("psi_table:size=1073741824", "psi_table:size=1073741824: size must be an integer <= 8192 "
                                  "(the table takes 16 B per entry: 1 GiB at 8192)"),
    ("ode:rtol=0", "ode:rtol=0: rtol must be a number >= 1e-15"),
    ("riemann:n=64.5", "riemann:n=64.5: n must be an integer in [1, 1e9]"),
    ("riemann:m=4", "riemann:m=4: unknown parameter 'm' (riemann takes n, dt, order, correction, ref_dt)"),
]


@pytest.mark.parametrize("spec,why", INVALID_SPECS)
def test_invalid_method_spec_raises_input_error_with_the_cli_line(spec, why):
    path = os.path.join(CASES, "paper-figure-2.json")
    with pytest.raises(rayint.InputError) as err:
        rayint.evaluate(path, methods=["exact", spec], timing=False)
    assert str(err.value) == why
    with pytest.raises(rayint.InputError) as err:
        rayint.integrate(spec, path)
    assert str(err.value) == why
    r = cli("eval", path, "--no-timing", "--methods", spec)
    assert r.returncode == 2
    assert r.stdout == ""
    assert r.stderr == "rayint: error: --methods " + why + "\n"


def test_unknown_method_is_input_error():
    with pytest.raises(rayint.InputError, match="nosuch: unknown method 'nosuch'"):
        rayint.integrate("nosuch", os.path.join(CASES, "paper-figure-2.json"))


def test_a_failed_method_is_null_and_counted_not_zero():
    path = os.path.join(CASES, "per-channel-densities.json")
    res = rayint.evaluate(path, methods=["exact", "particle"], timing=False)
    case = res["cases"][0]
    assert res["failed"] == len(case["rays"]) == 3
    for ray in case["rays"]:
        p = ray["methods"]["particle"]
        assert p["failed"] is True
        assert p["failure"].startswith("particle: needs a single transfer function")
        for field in ("intensity", "rel_error", "abs_error", "ulp_error", "seconds_per_ray"):
            assert p[field] is None
        assert ray["methods"]["exact"]["failed"] is False
        assert all(isinstance(x, float) for x in ray["methods"]["exact"]["rel_error"])
    summary = {s["method"]: s for s in case["summary"]}
    assert summary["particle"]["failed"] == 3 and summary["particle"]["max_rel_error"] is None
    assert summary["exact"]["failed"] == 0 and summary["exact"]["max_rel_error"] < EXACT_REL
    r = cli("eval", path, "--no-timing", "-q", "--methods", "exact,particle")
    assert r.returncode == 1  # written, a method failed on some ray (docs/exit-codes.md)
    assert json.loads(r.stdout)["cases"][0]["summary"] == case["summary"]


def test_methods_is_the_table_the_validator_uses():
    table = rayint.methods()
    assert [m["name"] for m in table] == rayint.method_names()
    n = next(p for m in table if m["name"] == "riemann" for p in m["params"] if p["name"] == "n")
    assert (n["type"], n["default"], n["min"], n["max"]) == ("integer", "64", 1, 1e9)
