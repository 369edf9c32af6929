// rayint_cell_accuracy: the double path of cells/cell_integral.hpp against the 50-digit reference
// (reference/cell_reference.hpp) on distorted linear cells of every type, and its cost per chord.
// Writes a JSON summary and a markdown table (reports/cells/; committed with this command):
//
//   build/tools/rayint_cell_accuracy --rays 200 --seed 1 --json reports/cells/accuracy.json
//       --markdown reports/cells/accuracy.md
//
// Families (each cell: nodes of the reference cell scaled to edge 1, then distorted):
//   tetra              random perturbation of every node by up to 30 % of the edge (always affine)
//   voxel_box          axis-aligned box with random edge lengths (VTK's voxel; affine)
//   voxel_perturbed    voxel node order, every node perturbed by 10-30 % of the edge
//   hex_twisted        top face rotated about the cell axis by 10-40 degrees, plus 10 % noise
//   hex_perturbed      every node perturbed by 10-30 % of the edge
//   wedge_vtk          VTK's documented orientation, perturbed by 10-30 %
//   wedge_gmsh         the same mirrored (z -> -z): gmsh's prism orientation, negative Jacobian
//   pyramid_warped     base corners moved out of plane by up to 30 %, apex moved by up to 30 %
// Rays: a random interior point (parametric coordinates uniform in the domain) and a uniformly
// random direction; the chord from cells/linear_cells.hpp's chord(). Transfer functions: three
// channels with 4-5 breakpoints inside the value range [0, 1] and optical depths up to ~5 per
// cell. Error: per channel |double - reference| / reference, for emission and optical depth
// (the reference's own bound is checked to be below 1e-25 of its value).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/cells/vtk_split.hpp"
#include "rayint/reference/cell_reference.hpp"
#include "cell_samples.hpp"  // tests/: the transfer functions and reference input shared with the tests

using namespace rayint;

namespace {

struct Family {
  const char* name;
  LinearCellType type;
};

const Family kFamilies[] = {
    {"tetra", LinearCellType::tetra},           {"voxel_box", LinearCellType::voxel},
    {"voxel_perturbed", LinearCellType::voxel}, {"hex_twisted", LinearCellType::hexahedron},
    {"hex_perturbed", LinearCellType::hexahedron}, {"wedge_vtk", LinearCellType::wedge},
    {"wedge_gmsh", LinearCellType::wedge},      {"pyramid_warped", LinearCellType::pyramid},
};

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    if (v.norm() > 1e-3) return v.normalized();
  }
}

LinearCell make_family_cell(const std::string& family, LinearCellType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double amount = 0.1 + 0.2 * u(rng);  // 10-30 % of the edge
  std::vector<Vec3> nodes;
  for (const Vec3& r : linear_reference_nodes(type)) nodes.push_back(r);
  if (family == "voxel_box") {
    const Vec3 size(0.5 + u(rng), 0.5 + u(rng), 0.5 + u(rng));
    for (Vec3& x : nodes) x = x.cwiseProduct(size);
  } else if (family == "hex_twisted") {
    const double angle = (10.0 + 30.0 * u(rng)) * 3.14159265358979323846 / 180.0;
    for (Vec3& x : nodes) {
      if (x[2] == 1.0) {
        const double cx = x[0] - 0.5, cy = x[1] - 0.5;
        x[0] = 0.5 + std::cos(angle) * cx - std::sin(angle) * cy;
        x[1] = 0.5 + std::sin(angle) * cx + std::cos(angle) * cy;
      }
      x += 0.1 * (2.0 * Vec3(u(rng), u(rng), u(rng)) - Vec3::Ones()) / std::sqrt(3.0);
    }
  } else if (family == "pyramid_warped") {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (i < 4) nodes[i][2] += amount * (2.0 * u(rng) - 1.0);
      else nodes[i] = Vec3(0.5, 0.5, 1.0) + amount * (2.0 * Vec3(u(rng), u(rng), u(rng)) - Vec3::Ones());
    }
  } else {
    const double a = family == "tetra" ? 0.3 : amount;
    for (Vec3& x : nodes) x += a * (2.0 * Vec3(u(rng), u(rng), u(rng)) - Vec3::Ones()) / std::sqrt(3.0);
  }
  if (family == "wedge_gmsh")
    for (Vec3& x : nodes) x[2] = -x[2];
  std::vector<double> values;
  for (std::size_t i = 0; i < nodes.size(); ++i) values.push_back(u(rng));
  return make_linear_cell(type, nodes, values);
}

// The same ray through VTK's split of the cell (random distinct global ids, as an unstructured
// grid), each tetra's chord integrated by the exact path and composited front to back.
bool split_integral(const LinearCellIntegrator& integrator, const LinearCell& cell, const ViewRay& ray, std::mt19937& rng,
                    CellPieceIntegral& out) {
  const int n = linear_node_count(cell.type);
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) ids[static_cast<std::size_t>(i)] = i;
  std::shuffle(ids.begin(), ids.end(), rng);
  struct Part {
    double t0;
    CellPieceIntegral r;
  };
  std::vector<Part> parts;
  for (const std::array<int, 4>& tet : vtk_split(cell.type, ids.data())) {
    std::vector<Vec3> nodes;
    std::vector<double> values;
    for (int k : tet) {
      nodes.push_back(cell.x[static_cast<std::size_t>(k)]);
      values.push_back(cell.value[static_cast<std::size_t>(k)]);
    }
    const LinearCell t = make_linear_cell(LinearCellType::tetra, nodes, values);
    const Chord ch = chord(t, ray);
    if (ch.failed) return false;
    for (const ChordInterval& iv : ch.intervals) parts.push_back({iv.t_near, integrator.integrate(t, ray, iv.t_near, iv.t_far)});
  }
  std::sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.t0 < b.t0; });
  out = CellPieceIntegral{};
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) out = composite(it->r, out);  // far -> near
  return out.converged;
}

double rel(double x, double ref) { return ref == 0.0 ? std::abs(x) : std::abs(x - ref) / std::abs(ref); }

struct Stats {
  std::string family, path;
  int rays = 0, chords = 0, failed_double = 0, failed_reference = 0, estimate_below_error = 0;
  double worst_emission = 0.0, worst_depth = 0.0, worst_reference_bound = 0.0, worst_abs = 0.0;
  std::vector<double> errors;
  double seconds_double = 0.0;
  std::vector<double> split_diffs;  // max over channels |E_split - E_ref| / E_ref, per ray
  int split_failed = 0;
  long pieces = 0, samples = 0;
  int max_degree = 0;
};

}  // namespace

int main(int argc, char** argv) {
  int rays = 200;
  unsigned seed = 1;
  std::string json_path, markdown_path, only_family;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--rays") rays = std::atoi(argv[i + 1]);
    else if (a == "--seed") seed = static_cast<unsigned>(std::atoi(argv[i + 1]));
    else if (a == "--json") json_path = argv[i + 1];
    else if (a == "--markdown") markdown_path = argv[i + 1];
    else if (a == "--family") only_family = argv[i + 1];  // one family only (diagnosis)
    else {
      std::cerr << "rayint_cell_accuracy: unknown option " << a << "\n";
      return 2;
    }
  }
  if (rays < 1) {
    std::cerr << "rayint_cell_accuracy: --rays must be >= 1\n";
    return 2;
  }
  const TransferFunctions tf = test::breakpoint_tf();
  const LinearCellIntegrator integrator(tf);
  std::vector<Stats> all;
  for (const Family& fam : kFamilies) {
    const unsigned family_index = static_cast<unsigned>(&fam - kFamilies);
    std::mt19937 rng(seed * 1000003u + family_index);
    if (!only_family.empty() && only_family != fam.name) continue;
    Stats st;
    st.family = fam.name;
    for (int r = 0; r < rays; ++r) {
      const LinearCell cell = make_family_cell(fam.name, fam.type, rng);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      Vec3 p;
      do p = Vec3(u(rng), u(rng), u(rng));
      while (!inside_reference(fam.type, p));
      const Vec3 target = cell_position(cell, p), dir = random_unit(rng);
      const ViewRay ray{target - 3.0 * dir, dir};
      const Chord ch = chord(cell, ray);
      ++st.rays;
      if (ch.failed) ++st.failed_double;
      for (const ChordInterval& iv : ch.intervals) {
        ++st.chords;
        const auto t0 = std::chrono::steady_clock::now();
        const CellPieceIntegral d = integrator.integrate(cell, ray, iv.t_near, iv.t_far);
        st.seconds_double += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        st.path = cell_path_name(d.path);
        st.pieces += d.pieces;
        st.samples += d.samples;
        st.max_degree = std::max(st.max_degree, d.max_degree);
        if (!d.converged) {
          ++st.failed_double;
          continue;
        }
        const CellReferenceInput in = test::reference_input(cell, ray, iv.t_near, iv.t_far);
        CellReference ref;
        try {
          ref = reference_cell_chord(tf, in);
        } catch (const std::exception& e) {
          ++st.failed_reference;
          std::cerr << fam.name << " ray " << r << ": reference failed: " << e.what() << "\n";
          continue;
        }
        double chord_worst = 0.0, chord_abs = 0.0;
        for (std::size_t c = 0; c < kChannels; ++c) {
          const double e = rel(d.emission[c], ref.emission[c]), o = rel(d.optical_depth[c], ref.optical_depth[c]);
          st.worst_emission = std::max(st.worst_emission, e);
          st.worst_depth = std::max(st.worst_depth, o);
          chord_worst = std::max({chord_worst, e, o});
          chord_abs = std::max(chord_abs, std::abs(d.emission[c] - ref.emission[c]) +
                                              std::abs(d.optical_depth[c] - ref.optical_depth[c]));
          if (ref.emission[c] > 0)
            st.worst_reference_bound = std::max(st.worst_reference_bound, ref.emission_error[c] / ref.emission[c]);
        }
        if (chord_abs > d.error_estimate) ++st.estimate_below_error;
        if (chord_worst > 1e-13)
          std::cerr << fam.name << " ray " << r << ": relative error " << chord_worst << ", absolute " << chord_abs
                    << ", estimate " << d.error_estimate << ", pieces " << d.pieces << ", degree " << d.max_degree
                    << ", reference pieces " << ref.pieces << "\n";
        if (ch.intervals.size() == 1) {  // the split against the own interpolation on the same ray
          CellPieceIntegral sp;
          if (!split_integral(integrator, cell, ray, rng, sp)) {
            ++st.split_failed;
          } else {
            // Scaled by the largest channel's emission: a channel whose emission is near 0 would
            // make a per-channel relative difference meaningless.
            double diff = 0.0, scale = 0.0;
            for (std::size_t c = 0; c < kChannels; ++c) {
              diff = std::max(diff, std::abs(sp.emission[c] - ref.emission[c]));
              scale = std::max(scale, ref.emission[c]);
            }
            st.split_diffs.push_back(scale > 0.0 ? diff / scale : diff);
          }
        }
        st.worst_abs = std::max(st.worst_abs, chord_abs);
        st.errors.push_back(chord_worst);
      }
    }
    std::sort(st.errors.begin(), st.errors.end());
    std::sort(st.split_diffs.begin(), st.split_diffs.end());
    std::cerr << fam.name << ": " << st.chords << " chords, worst emission " << st.worst_emission << ", depth "
              << st.worst_depth << "\n";
    all.push_back(std::move(st));
  }
  auto median = [](const std::vector<double>& v) { return v.empty() ? 0.0 : v[v.size() / 2]; };
  if (!json_path.empty()) {
    std::ofstream js(json_path);
    js << "{\n  \"generator\": \"build/tools/rayint_cell_accuracy --rays " << rays << " --seed " << seed
       << "\",\n  \"families\": [\n";
    for (std::size_t k = 0; k < all.size(); ++k) {
      const Stats& s = all[k];
      char buf[1024];
      std::snprintf(buf, sizeof buf,
                    "    {\"family\": \"%s\", \"path\": \"%s\", \"rays\": %d, \"chords\": %d, \"failed_double\": %d, "
                    "\"failed_reference\": %d, \"worst_emission_rel\": %.3e, \"worst_depth_rel\": %.3e, \"worst_abs\": %.3e, "
                    "\"median_rel\": %.3e, \"estimate_below_error\": %d, \"worst_reference_bound_rel\": %.3e, "
                    "\"us_per_chord\": %.3f, \"pieces_per_chord\": %.2f, \"samples_per_chord\": %.1f, \"max_degree\": %d, \"split_rays\": %zu, \"split_median_rel\": %.3e, \"split_worst_rel\": %.3e}%s\n",
                    s.family.c_str(), s.path.c_str(), s.rays, s.chords, s.failed_double, s.failed_reference,
                    s.worst_emission, s.worst_depth, s.worst_abs, median(s.errors), s.estimate_below_error,
                    s.worst_reference_bound, 1e6 * s.seconds_double / std::max(1, s.chords),
                    static_cast<double>(s.pieces) / std::max(1, s.chords),
                    static_cast<double>(s.samples) / std::max(1, s.chords), s.max_degree, s.split_diffs.size(),
                    median(s.split_diffs), s.split_diffs.empty() ? 0.0 : s.split_diffs.back(), k + 1 < all.size() ? "," : "");
      js << buf;
    }
    js << "  ]\n}\n";
  }
  if (!markdown_path.empty()) {
    std::ofstream md(markdown_path);
    md << "# Linear cells in their own interpolation: double path vs 50-digit reference\n\n"
       << "Made by `build/tools/rayint_cell_accuracy --rays " << rays << " --seed " << seed
       << "` (tools/cell_accuracy.cpp; families and transfer functions described there). One random ray "
          "through each of `rays` random cells per family; error = max over channels of |double - ref| / ref "
          "for emission and optical depth; `worst abs`: max over channels of |dE| + |dD| (emissions and depths are O(0.01-1) here). `est<err`: chords whose error exceeded the double path's own "
          "error_estimate. Time: the double path's `LinearCellIntegrator::integrate` per chord on this machine "
          "(shared, 2 cores; indicative only). `split`: the same ray through VTK's tetrahedralisation of the "
          "cell (cells/vtk_split.hpp, random global ids, tets by the exact path) against the 50-digit "
          "own-interpolation reference: max over channels of |E_split - E_ref| / (largest channel's E_ref), rays whose "
          "chord is one interval.\n\n"
       << "| family | path | chords | failed (double / ref) | worst emission rel | worst depth rel | worst abs | median rel | est<err | us/chord | pieces/chord | samples/chord | max degree | split: rays | split median | split worst |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Stats& s : all) {
      char buf[512];
      std::snprintf(buf, sizeof buf, "| %s | %s | %d | %d / %d | %.2e | %.2e | %.2e | %.2e | %d | %.1f | %.2f | %.1f | %d | %zu | %.2e | %.2e |\n",
                    s.family.c_str(), s.path.c_str(), s.chords, s.failed_double, s.failed_reference,
                    s.worst_emission, s.worst_depth, s.worst_abs, median(s.errors), s.estimate_below_error,
                    1e6 * s.seconds_double / std::max(1, s.chords), static_cast<double>(s.pieces) / std::max(1, s.chords),
                    static_cast<double>(s.samples) / std::max(1, s.chords), s.max_degree, s.split_diffs.size(),
                    median(s.split_diffs), s.split_diffs.empty() ? 0.0 : s.split_diffs.back());
      md << buf;
    }
  }
  return 0;
}
