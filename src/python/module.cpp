// module.cpp -- rayint as a Python module (pybind11): the compiled half, `rayint._rayint`.
//
// Every function calls the library code the CLI calls, so the numbers are the CLI's bit for bit:
//   _exact_pieces   integrators/exact_batch (exact_piece in a loop), GIL released;
//   _exact_grad, _exact_ray_grad  integrators/exact_grad (a piece's / a ray's exact gradient);
//   _evaluate       studies/evaluate_case + report/eval_report_json (`rayint eval`); a mesh of
//                   cells other than tetrahedra: studies/evaluate_own_cells + report/own_eval_json;
//   _reference      studies/reference_rays + report/to_json(ReferenceRay);
//   _check          studies/check_candidate (own cells: check_candidate_own) +
//                   report/check_report_json (`rayint check`);
// The three take `split` (`--cells split`: VTK's tetrahedralisation of such cells).
//   _integrate      any registered method by its spec on arrays of segments;
//   _composite      integrators/nerf (nerf_composite, pl_nerf_composite) on explicit samples;
//   _mixed_regime_pieces, _regime_names  the benchmark's pieces (generators/), for timing.
// Reports cross as JSON text (nlohmann's dump is round-trip exact for doubles; json.loads on the
// Python side). Cases and candidates come as a path (read as the CLI reads it, so the messages name
// the file) or as JSON text with a source name. rayint::InputError becomes rayint.InputError (a
// ValueError) with the CLI's one-line message (the CLI prints it after "rayint: error: "), and so
// does a method spec that is not valid (rayint::MethodSpecError);
// std::invalid_argument becomes ValueError, other std::exceptions RuntimeError (pybind11).
// src/python/rayint/__init__.py holds the Python-facing signatures, broadcasting and docs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/report/method_table.hpp"
#include "rayint/core/format.hpp"
#include "rayint/generators/regimes.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/integrators/exact_batch.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/nerf.hpp"
#include "rayint/report/cell_render_json.hpp"
#include "rayint/report/check_json.hpp"
#include "rayint/report/evaluation_json.hpp"
#include "rayint/studies/check.hpp"
#include "rayint/studies/evaluate.hpp"
#include "rayint/studies/own_cells_eval.hpp"

namespace py = pybind11;
using rayint::Case;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A case or candidate as the Python side hands it: (is_path, path or JSON text, source name).
struct Document {
  bool is_path = false;
  std::string text;
  std::string source;
};

// `split`: cells other than tetrahedra through VTK's tetrahedralisation (`--cells split`).
rayint::MeshReadOptions mesh_options(bool split) {
  rayint::MeshReadOptions o;
  o.split_cells = split;
  return o;
}

// For a mesh case, `*repairs` (when given) receives what reading its mesh reoriented and dropped;
// a mesh of cells other than tetrahedra (not split) goes to `*own` when given (refused without).
Case load_case(const Document& d, bool split, std::optional<rayint::TetRepairs>* repairs = nullptr,
               std::optional<rayint::MeshCase>* own = nullptr) {
  return d.is_path ? rayint::read_case_file(d.text, mesh_options(split), repairs, own)
                   : rayint::parse_case_text(d.text, d.source, mesh_options(split), repairs, own);
}

// Every case the documents name (a folder: every case file in it, as `rayint eval`), each with
// its mesh repairs (empty for a case without a mesh); cases of cells other than tetrahedra in
// their own interpolation go to `own` instead.
std::vector<Case> load_cases(const std::vector<Document>& docs, bool split,
                             std::vector<std::optional<rayint::TetRepairs>>& repairs,
                             std::vector<rayint::MeshCase>& own) {
  std::vector<Case> cases;
  const auto add = [&](auto&& read) {
    repairs.emplace_back();
    std::optional<rayint::MeshCase> own_case;
    Case c = read(&repairs.back(), &own_case);
    if (own_case) {
      repairs.pop_back();
      own.push_back(std::move(*own_case));
    } else {
      cases.push_back(std::move(c));
    }
  };
  for (const Document& d : docs) {
    if (d.is_path && std::filesystem::is_directory(d.text)) {
      const std::vector<std::string> files = rayint::list_case_files(d.text);
      if (files.empty()) throw rayint::InputError(d.text + ": folder holds no case files (*.json)");
      for (const auto& f : files)
        add([&](auto* r, auto* o) { return rayint::read_case_file(f, mesh_options(split), r, o); });
    } else {
      add([&](auto* r, auto* o) { return load_case(d, split, r, o); });
    }
  }
  return cases;
}

std::vector<rayint::MethodSpec> methods_of(const std::string& csv) {
  return csv.empty() ? rayint::default_methods() : rayint::parse_method_list(csv);
}

// field::fail with `what` about element `i` of `name` (messages like the case reader's).
[[noreturn]] void bad_value(const char* function, const char* name, std::size_t i,
                            const char* what, double got) {
  rayint::field::fail(function, rayint::field::index_path(name, i),
                      std::string(what) + ", got " + rayint::format_number(got));
}

// The five piece arrays of exact_pieces and exact_grad: their common size, or one line naming
// `function` when they differ.
std::size_t piece_count(const char* function, const Array& rho_exit, const Array& rho_far,
                        const Array& kappa_exit, const Array& kappa_far, const Array& length) {
  const std::size_t n = static_cast<std::size_t>(rho_exit.size());
  for (const Array* a : {&rho_far, &kappa_exit, &kappa_far, &length})
    if (static_cast<std::size_t>(a->size()) != n)
      throw std::invalid_argument(std::string(function) + ": the five arrays must have the same size");
  return n;
}

// Every piece in the exact path's domain: densities and length finite and >= 0, colours finite;
// bad_value naming `function`, the array and the index otherwise. Needs no GIL.
void check_pieces(const char* function, const double* rho_exit, const double* rho_far, const double* kappa_exit,
                  const double* kappa_far, const double* length, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(rho_exit[i]) && rho_exit[i] >= 0.0))
      bad_value(function, "rho_exit", i, "must be finite and >= 0", rho_exit[i]);
    if (!(std::isfinite(rho_far[i]) && rho_far[i] >= 0.0))
      bad_value(function, "rho_far", i, "must be finite and >= 0", rho_far[i]);
    if (!std::isfinite(kappa_exit[i])) bad_value(function, "kappa_exit", i, "must be finite", kappa_exit[i]);
    if (!std::isfinite(kappa_far[i])) bad_value(function, "kappa_far", i, "must be finite", kappa_far[i]);
    if (!(std::isfinite(length[i]) && length[i] >= 0.0))
      bad_value(function, "length", i, "must be finite and >= 0", length[i]);
  }
}

py::tuple exact_pieces(const Array& rho_exit, const Array& rho_far, const Array& kappa_exit,
                       const Array& kappa_far, const Array& length) {
  const std::size_t n = piece_count("exact_pieces", rho_exit, rho_far, kappa_exit, kappa_far, length);
  Array emission(static_cast<py::ssize_t>(n)), transmittance(static_cast<py::ssize_t>(n));
  // The batched exact path (integrators/exact_batch.hpp), the one `exact` itself uses.
  const rayint::PieceColumns in{length.data(), rho_far.data(), rho_exit.data(), kappa_far.data(),
                                kappa_exit.data(), n};
  rayint::OpticsColumns out;
  out.emission = emission.mutable_data();
  out.transmittance = transmittance.mutable_data();
  {
    py::gil_scoped_release release;
    check_pieces("exact_pieces", in.rho_exit, in.rho_far, in.kappa_exit, in.kappa_far, in.length, n);
    rayint::exact_batch(in, out);
  }
  return py::make_tuple(emission, transmittance);
}

// exact_grad: integrators/exact_grad.hpp's exact_piece_grad on every piece (issue 28): emission,
// transmittance and their derivatives with respect to the five inputs, GIL released.
py::tuple exact_grad(const Array& rho_exit, const Array& rho_far, const Array& kappa_exit,
                     const Array& kappa_far, const Array& length) {
  const std::size_t n = piece_count("exact_grad", rho_exit, rho_far, kappa_exit, kappa_far, length);
  constexpr int kOut = 10;
  std::vector<Array> out;
  for (int k = 0; k < kOut; ++k) out.emplace_back(static_cast<py::ssize_t>(n));
  double* o[kOut];
  for (int k = 0; k < kOut; ++k) o[k] = out[static_cast<std::size_t>(k)].mutable_data();
  const double *re = rho_exit.data(), *rf = rho_far.data(), *ke = kappa_exit.data(),
               *kf = kappa_far.data(), *len = length.data();
  {
    py::gil_scoped_release release;
    check_pieces("exact_grad", re, rf, ke, kf, len, n);
    for (std::size_t i = 0; i < n; ++i) {
      const rayint::PieceOpticsGrad g = rayint::exact_piece_grad({len[i], rf[i], re[i], kf[i], ke[i]});
      const double v[kOut] = {g.optics.emission, g.optics.transmittance, g.de_rho_exit, g.de_rho_far,
                              g.de_kappa_exit, g.de_kappa_far, g.de_length, g.dt_rho_exit,
                              g.dt_rho_far, g.dt_length};
      for (int k = 0; k < kOut; ++k) o[k][i] = v[k];
    }
  }
  py::tuple t(kOut);
  for (int k = 0; k < kOut; ++k) t[static_cast<std::size_t>(k)] = out[static_cast<std::size_t>(k)];
  return t;
}

// One ray's exact gradient (integrators/exact_grad.hpp, exact_ray_gradient): segments far ->
// near as arrays, the background, and the six functions (density r, g, b, color r, g, b) as
// (positions, values) pairs. Returns (intensity (3,), background (3,), length (n, 3),
// scalar_far (n, 3), scalar_exit (n, 3), [six (k, 2) arrays of d/d position, d/d value]).
py::tuple exact_ray_grad(const Array& length, const Array& scalar_far, const Array& scalar_exit,
                         const Array& background, const std::vector<std::pair<Array, Array>>& functions) {
  const std::size_t n = static_cast<std::size_t>(length.size());
  if (static_cast<std::size_t>(scalar_far.size()) != n || static_cast<std::size_t>(scalar_exit.size()) != n)
    throw std::invalid_argument("exact_ray_grad: length, scalar_far and scalar_exit must have the same size");
  if (background.size() != 3) throw std::invalid_argument("exact_ray_grad: background must have 3 entries");
  if (functions.size() != 6)
    throw std::invalid_argument("exact_ray_grad: six functions (density r, g, b, color r, g, b)");
  rayint::Ray ray;
  for (int c = 0; c < 3; ++c) ray.background[static_cast<std::size_t>(c)] = background.data()[c];
  for (std::size_t j = 0; j < n; ++j) {
    if (!(std::isfinite(length.data()[j]) && length.data()[j] >= 0.0))
      bad_value("exact_ray_grad", "length", j, "must be finite and >= 0", length.data()[j]);
    ray.segments.push_back({length.data()[j], scalar_far.data()[j], scalar_exit.data()[j]});
  }
  rayint::TransferFunctions tf;
  const char* names[6] = {"density r", "density g", "density b", "color r", "color g", "color b"};
  for (std::size_t f = 0; f < 6; ++f) {
    const auto& [pos, val] = functions[f];
    if (pos.size() != val.size() || pos.size() < 1)
      throw std::invalid_argument(std::string("exact_ray_grad: ") + names[f] +
                                  ": positions and values must have the same size, at least 1");
    rayint::PiecewiseLinear pl;
    for (py::ssize_t k = 0; k < pos.size(); ++k) {
      const double p = pos.data()[k], v = val.data()[k];
      if (!std::isfinite(p) || (k > 0 && !(p > pl.scalar.back())))
        throw std::invalid_argument(std::string("exact_ray_grad: ") + names[f] +
                                    ": positions must be finite and strictly increasing");
      if (!(std::isfinite(v) && v >= 0.0))
        throw std::invalid_argument(std::string("exact_ray_grad: ") + names[f] + ": values must be finite and >= 0");
      pl.scalar.push_back(p);
      pl.value.push_back(v);
    }
    (f < 3 ? tf.density : tf.color)[f % 3] = pl;
  }
  rayint::RayGradient g;
  {
    py::gil_scoped_release release;
    rayint::exact_ray_gradient(tf, ray, g);
  }
  Array intensity(3), bg(3);
  Array len_out({static_cast<py::ssize_t>(n), py::ssize_t{3}}), far_out({static_cast<py::ssize_t>(n), py::ssize_t{3}}),
      exit_out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  for (int c = 0; c < 3; ++c) {
    intensity.mutable_data()[c] = g.intensity[static_cast<std::size_t>(c)];
    bg.mutable_data()[c] = g.background[static_cast<std::size_t>(c)];
  }
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t c = 0; c < 3; ++c) {
      len_out.mutable_data()[3 * j + c] = g.length[j][c];
      far_out.mutable_data()[3 * j + c] = g.scalar_far[j][c];
      exit_out.mutable_data()[3 * j + c] = g.scalar_exit[j][c];
    }
  py::list nodes;
  for (std::size_t f = 0; f < 6; ++f) {
    const auto& d = (f < 3 ? g.density : g.color)[f % 3];
    Array a({static_cast<py::ssize_t>(d.size()), py::ssize_t{2}});
    for (std::size_t k = 0; k < d.size(); ++k) {
      a.mutable_data()[2 * k] = d[k].position;
      a.mutable_data()[2 * k + 1] = d[k].value;
    }
    nodes.append(a);
  }
  return py::make_tuple(intensity, bg, len_out, far_out, exit_out, nodes);
}

std::string evaluate(const std::vector<Document>& docs, const std::string& methods_csv,
                     bool timing, unsigned threads, bool split) {
  const std::vector<rayint::MethodSpec> methods = methods_of(methods_csv);
  py::gil_scoped_release release;
  std::vector<std::optional<rayint::TetRepairs>> repairs;
  std::vector<rayint::MeshCase> own;
  const std::vector<Case> cases = load_cases(docs, split, repairs, own);  // validate all before evaluating any
  if (!own.empty()) {  // as `rayint eval`: alone, one method (the own interpolation), with its reference
    rayint::require_own_cases_alone(own, cases.empty() ? std::string() : cases.front().source,
                                    !methods_csv.empty(), "methods", "cells='split'");
    std::vector<rayint::OwnCaseEvaluation> results;
    for (const rayint::MeshCase& mc : own) results.push_back(rayint::evaluate_own_cells(mc, true, threads));
    return rayint::own_eval_json(results, true).dump();
  }
  rayint::EvalOptions eo;
  eo.measure_time = timing;
  eo.threads = threads;
  std::vector<rayint::CaseEvaluation> results;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    results.push_back(rayint::evaluate_case(cases[i], methods, eo));
    results.back().mesh_repairs = repairs[i];
  }
  return rayint::eval_report_json(results).dump();
}

std::string reference(const Document& doc, unsigned threads, bool split) {
  py::gil_scoped_release release;
  std::optional<rayint::MeshCase> own;
  const Case c = load_case(doc, split, nullptr, &own);
  if (own)
    throw rayint::InputError(own->source + ": mesh_file: cells other than tetrahedra: their 50-digit reference in "
                             "the own interpolation comes with evaluate() (each ray's \"reference\"); "
                             "cells='split' gives VTK's tetrahedralisation");
  nlohmann::json rays = nlohmann::json::array();
  for (const auto& r : rayint::reference_rays(c, threads)) rays.push_back(rayint::to_json(r));
  return nlohmann::json{{"case", c.name}, {"rays", rays}}.dump();
}

std::pair<std::string, bool> check(const Document& case_doc, const Document& candidate_doc,
                                   double rel_tol, double abs_tol, bool with_reference,
                                   unsigned threads, bool split) {
  py::gil_scoped_release release;
  std::optional<rayint::MeshCase> own;  // cells other than tetrahedra: studies/check.hpp check_candidate_own
  const Case c = load_case(case_doc, split, nullptr, &own);
  const rayint::Candidate candidate = rayint::read_case_candidate(
      candidate_doc.text, candidate_doc.is_path, candidate_doc.source, c, own ? &*own : nullptr);
  for (const double tol : {rel_tol, abs_tol})
    if (!(std::isfinite(tol) && tol >= 0.0))
      throw std::invalid_argument("check: tolerances must be finite numbers >= 0, got " +
                                  rayint::format_number(tol));
  rayint::CheckOptions co;
  co.rel_tol = rel_tol;
  co.abs_tol = abs_tol;
  co.with_reference = with_reference;
  co.threads = threads;
  const rayint::CheckResult result =
      own ? rayint::check_candidate_own(*own, candidate, co) : rayint::check_candidate(c, candidate, co);
  return {rayint::check_report_json(result).dump(), result.pass};
}

// Rays from arrays of shape (rays, segments) (all three the same) and background (rays, 3).
py::tuple integrate(const std::string& method, const Document& doc, const Array& length,
                    const Array& scalar_far, const Array& scalar_exit, const Array& background,
                    bool from_arrays) {
  const rayint::MethodSpec spec = rayint::parse_method_spec(method);
  std::vector<rayint::Ray> arrays_rays;
  if (from_arrays) {
    if (length.ndim() != 2 || scalar_far.ndim() != 2 || scalar_exit.ndim() != 2 ||
        background.ndim() != 2 || background.shape(1) != rayint::kChannels)
      throw std::invalid_argument("integrate: expected arrays of shape (rays, segments) and a "
                                  "background of shape (rays, 3)");
    const auto rays = static_cast<std::size_t>(length.shape(0));
    const auto segs = static_cast<std::size_t>(length.shape(1));
    if (static_cast<std::size_t>(background.shape(0)) != rays) 
      throw std::invalid_argument("integrate: background must have one row per ray");
    for (const Array* a : {&scalar_far, &scalar_exit})
      if (static_cast<std::size_t>(a->shape(0)) != rays ||
          static_cast<std::size_t>(a->shape(1)) != segs)
        throw std::invalid_argument("integrate: length, scalar_far and scalar_exit must have the "
                                    "same shape");
    arrays_rays.resize(rays);
    for (std::size_t r = 0; r < rays; ++r) {
      rayint::Ray& ray = arrays_rays[r];
      for (int c = 0; c < rayint::kChannels; ++c) {
        const double b = background.at(r, c);
        if (!(std::isfinite(b) && b >= 0.0))
          bad_value("integrate", "background", r * 3 + static_cast<std::size_t>(c),
                    "must be finite and >= 0", b);
        ray.background[c] = b;
      }
      for (std::size_t s = 0; s < segs; ++s) {
        const std::size_t i = r * segs + s;
        const double L = length.data()[i], sf = scalar_far.data()[i], se = scalar_exit.data()[i];
        if (!(std::isfinite(L) && L >= 0.0)) bad_value("integrate", "length", i, "must be finite and >= 0", L);
        if (!std::isfinite(sf)) bad_value("integrate", "scalar_far", i, "must be finite", sf);
        if (!std::isfinite(se)) bad_value("integrate", "scalar_exit", i, "must be finite", se);
        ray.segments.push_back({L, sf, se});
      }
    }
  }
  std::vector<double> intensity, transmittance;
  {
    py::gil_scoped_release release;
    const Case c = load_case(doc, false);
    const std::vector<rayint::Ray>& rays = from_arrays ? arrays_rays : c.rays;
    const auto integrator = rayint::make_integrator(spec, c.transfer);
    intensity.resize(rays.size() * 3);
    transmittance.resize(rays.size() * 3);
    for (std::size_t r = 0; r < rays.size(); ++r) {
      const rayint::RayResult res = integrator->integrate(rays[r], nullptr);
      for (int k = 0; k < rayint::kChannels; ++k) {
        intensity[r * 3 + static_cast<std::size_t>(k)] = res.intensity[k];
        transmittance[r * 3 + static_cast<std::size_t>(k)] = res.transmittance[k];
      }
    }
  }
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(intensity.size() / 3), 3};
  return py::make_tuple(Array(shape, intensity.data()), Array(shape, transmittance.data()));
}

// sigma (R, N), colour (R, 3, N), delta (R, N) for nerf; (R, N - 1) intervals for pl_nerf.
py::tuple composite(const Array& sigma, const Array& colour, const Array& delta, bool linear,
                    bool mid_colour) {
  if (sigma.ndim() != 2 || colour.ndim() != 3 || delta.ndim() != 2 ||
      colour.shape(1) != rayint::kChannels || colour.shape(0) != sigma.shape(0) ||
      colour.shape(2) != sigma.shape(1) || delta.shape(0) != sigma.shape(0) ||
      delta.shape(1) != sigma.shape(1) - (linear ? 1 : 0))
    throw std::invalid_argument("composite: sigma (rays, N), rgb (rays, N, 3) and the deltas do "
                                "not match");
  const auto rays = static_cast<std::size_t>(sigma.shape(0));
  const auto n = static_cast<std::size_t>(sigma.shape(1));
  const std::size_t steps = static_cast<std::size_t>(delta.shape(1));
  const char* fn = linear ? "pl_nerf_composite" : "nerf_composite";
  Array out_rgb(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rays), 3});
  Array out_t(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rays), 3});
  const double* s = sigma.data();
  const double* col = colour.data();
  const double* d = delta.data();
  double* rgb = out_rgb.mutable_data();
  double* tr = out_t.mutable_data();
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < rays * n; ++i)
      if (!(std::isfinite(s[i]) && s[i] >= 0.0)) bad_value(fn, "sigma", i, "must be finite and >= 0", s[i]);
    for (std::size_t i = 0; i < rays * steps; ++i)
      if (!(std::isfinite(d[i]) && d[i] >= 0.0)) bad_value(fn, "delta", i, "must be finite and >= 0", d[i]);
    for (std::size_t i = 0; i < rays * 3 * n; ++i)
      if (!std::isfinite(col[i])) bad_value(fn, "rgb", i, "must be finite", col[i]);
    for (std::size_t r = 0; r < rays; ++r)
      for (std::size_t c = 0; c < 3; ++c) {
        const rayint::CompositeResult res =
            linear ? rayint::pl_nerf_composite(s + r * n, col + (r * 3 + c) * n, d + r * steps,
                                               steps, mid_colour)
                   : rayint::nerf_composite(s + r * n, col + (r * 3 + c) * n, d + r * steps, n);
        rgb[r * 3 + c] = res.emission;
        tr[r * 3 + c] = res.transmittance;
      }
  }
  return py::make_tuple(out_rgb, out_t);
}

// The benchmark's mixed pieces (generators/regimes.hpp), as five arrays: for timing
// exact_pieces on the pieces bench/bench_exact.cpp BM_exact_pieces_batch times.
py::tuple mixed_regime_pieces(std::size_t count, std::uint64_t seed) {
  const std::vector<rayint::ChannelPiece> pieces = rayint::mixed_regime_pieces(count, seed);
  Array rho_exit(static_cast<py::ssize_t>(count)), rho_far(static_cast<py::ssize_t>(count)),
      kappa_exit(static_cast<py::ssize_t>(count)), kappa_far(static_cast<py::ssize_t>(count)),
      length(static_cast<py::ssize_t>(count));
  for (std::size_t i = 0; i < count; ++i) {
    rho_exit.mutable_data()[i] = pieces[i].rho_exit;
    rho_far.mutable_data()[i] = pieces[i].rho_far;
    kappa_exit.mutable_data()[i] = pieces[i].kappa_exit;
    kappa_far.mutable_data()[i] = pieces[i].kappa_far;
    length.mutable_data()[i] = pieces[i].length;
  }
  return py::make_tuple(rho_exit, rho_far, kappa_exit, kappa_far, length);
}

}  // namespace

PYBIND11_MODULE(_rayint, m) {
  m.doc() = "rayint's library (see rayint/__init__.py for the Python-facing functions)";
  static PyObject* input_error =
      py::register_exception<rayint::InputError>(m, "InputError", PyExc_ValueError).ptr();
  // A method spec that is not valid (unknown method or parameter, a value of the wrong type or
  // out of range) is bad input too: rayint.InputError with the CLI's message.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rayint::MethodSpecError& e) {
      PyErr_SetString(input_error, e.what());
    }
  });
  py::class_<Document>(m, "_Document")
      .def(py::init([](bool is_path, std::string text, std::string source) {
        return Document{is_path, std::move(text), std::move(source)};
      }));
  m.def("_exact_pieces", &exact_pieces);
  m.def("_exact_grad", &exact_grad);
  m.def("_exact_ray_grad", &exact_ray_grad);
  m.def("_evaluate", &evaluate);
  m.def("_reference", &reference);
  m.def("_check", &check);
  m.def("_integrate", &integrate);
  m.def("_composite", &composite);
  m.def("_method_names", &rayint::method_names);
  m.def("_methods_json", [] { return rayint::methods_json(rayint::method_table()).dump(); });
  m.def("_mixed_regime_pieces", &mixed_regime_pieces);
  m.def("_regime_names", [] {  // piece i of _mixed_regime_pieces is of regime i % len(names)
    std::vector<std::string> names;
    for (const rayint::Regime r : rayint::all_regimes()) names.push_back(rayint::regime_name(r));
    return names;
  });
}
