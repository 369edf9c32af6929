// Higher-order cells (src/rayint/cells/), the polynomial root splitting (model/polynomial.hpp),
// the 50-digit polynomial reference (reference/poly_reference.cpp), the polynomial ODE, and
// the decomposition into linear tetrahedra with its order of convergence. Hand-derived values
// are computed here in cpp_bin_float_50, independently of the reference.
#include <array>
#include <boost/math/special_functions/factorials.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "rayint/studies/cells_study.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/cells/cell.hpp"
#include "rayint/cells/poly_ode.hpp"
#include "rayint/cells/shape_functions.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/model/polynomial.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/reference/reference_detail.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using rayint::reference_detail::Real;

namespace {

struct CellTolerances {
  // Shape functions in double, O(1) terms: partition of unity and nodal values measured
  // <= 4.4e-16 off; 1e-14 leaves 20x.
  static constexpr double shape_abs = 1e-14;
  // cell_chord's multiplied-out polynomial against the shape functions at the same point
  // (values in [0, 1], |xi| <= ~1.5): measured <= 2.3e-15; 1e-13 leaves 40x.
  static constexpr double chord_poly_abs = 1e-13;
  // A root can only be as good as p's evaluation near it: |x - r| <~ eps * sum |c_k r^k| /
  // |p'(r)| (the root's condition). toms748 stops at 2 ulps of the bracket; the test allows
  // root_ulps times the condition bound (measured <= 0.4 of it on 300 polynomials, seed 9).
  static constexpr double root_ulps = 8.0;
  // ODE (Dormand-Prince 5(4), local control at rtol) against the reference on random cells:
  // global relative error measured <= 0.83 rtol (rtol 1e-6 and 1e-10, 60 rays, this file) and
  // <= 1.18 rtol (rtol 1e-8, `rayint cells --count 12 --rays 2`, seeds 1..4). Global error can
  // exceed the local tolerance by a small factor; 5 rtol is that factor with room.
  static constexpr double ode_per_rtol = 5.0;
  // Order of the decomposition error (expected 2: linear interpolation of a smooth scalar,
  // error O(h^2), transfer functions Lipschitz). Least-squares fit over levels 1..8 of the
  // median error, 12 cells x 2 rays per type, seeds 1..4: measured 1.87..2.26. 0.5 still tells
  // 2 from 1 and from 3.
  static constexpr double order_band = 0.5;
};

Real hand_value(const ExtendedValue& v) { return Real(v.hi) + Real(v.lo); }

double rel(const Real& x, const Real& exact) { return static_cast<double>(abs(x - exact) / abs(exact)); }

// The reference's intensity in channel 0 against a hand value; also checks the error bound.
void check_reference(const ReferenceRay& r, const Real& expected) {
  const Real got = hand_value(r.intensity[0]);
  INFO("reference " << r.intensity[0].hi << " expected " << static_cast<double>(expected));
  CHECK(rel(got, expected) <= test::Tolerances::reference_rel);
  CHECK(static_cast<double>(abs(got - expected)) <= r.error_bound[0]);
}

}  // namespace

TEST_CASE("cells: shape functions are a partition of unity and interpolate the nodes", "[cells]") {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (CellType type : {CellType::tet10, CellType::hex8, CellType::hex20}) {
    INFO(cell_type_name(type));
    const auto& nodes = reference_nodes(type);
    REQUIRE(static_cast<int>(nodes.size()) == node_count(type));
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const std::vector<double> N = shape_functions(type, nodes[j]);
      for (std::size_t i = 0; i < N.size(); ++i)
        CHECK(std::abs(N[i] - (i == j ? 1.0 : 0.0)) <= CellTolerances::shape_abs);
    }
    for (int n = 0; n < 100; ++n) {
      const Vec3 xi(u(rng), u(rng), u(rng));
      const std::vector<double> N = shape_functions(type, xi);
      double sum = 0, magnitude = 0;
      for (double x : N) {
        sum += x;
        magnitude += std::abs(x);
      }
      // Outside the cell the terms grow (tet10 up to ~60 here): rounding relative to them.
      CHECK(std::abs(sum - 1.0) <= CellTolerances::shape_abs * std::max(1.0, magnitude));
      // The factored form cell_chord multiplies out is the same function.
      const auto& products = shape_products(type);
      for (std::size_t i = 0; i < N.size(); ++i) {
        double p = products[i].scale;
        for (const auto& f : products[i].factors) p *= f.c0 + f.c1.dot(xi);
        CHECK(std::abs(p - N[i]) <= CellTolerances::shape_abs);
      }
    }
  }
  // The spans are the appendix's: tet10 reproduces x^2 + yz, hex8 xyz, hex20 x^2yz.
  struct Field { CellType type; double (*f)(const Vec3&); };
  const Field fields[] = {
      {CellType::tet10, [](const Vec3& x) { return x[0] * x[0] + x[1] * x[2] - 0.5 * x[2]; }},
      {CellType::hex8, [](const Vec3& x) { return x[0] * x[1] * x[2] + x[0] - 2.0; }},
      {CellType::hex20, [](const Vec3& x) { return x[0] * x[0] * x[1] * x[2] + x[1] * x[1]; }}};
  for (const auto& fld : fields) {
    std::vector<double> values;
    for (const Vec3& n : reference_nodes(fld.type)) values.push_back(fld.f(n));
    for (int n = 0; n < 50; ++n) {
      const Vec3 xi(u(rng), u(rng), u(rng));
      const std::vector<double> N = shape_functions(fld.type, xi);
      double s = 0;
      for (std::size_t i = 0; i < N.size(); ++i) s += N[i] * values[i];
      CHECK(s == Approx(fld.f(xi)).margin(1e-13));
    }
  }
}

TEST_CASE("cells: the polynomial along a ray equals the shape functions, degrees 2, 3, 4", "[cells]") {
  for (CellType type : {CellType::tet10, CellType::hex8, CellType::hex20}) {
    INFO(cell_type_name(type));
    double worst = 0.0, smallest_leading = 1e300;
    for (std::uint64_t k = 0; k < 20; ++k) {
      const HigherOrderCell cell = random_cell(type, 100 + k);
      const ViewRay ray = random_ray_through(cell, 200 + k);
      const CellChord chord = cell_chord(cell, ray);
      REQUIRE(chord.span.hit);
      REQUIRE(chord.segment.degree() == ray_degree(type));
      smallest_leading = std::min(smallest_leading, std::abs(chord.segment.coeffs.back()));
      for (int m = 0; m <= 10; ++m) {
        const double s = chord.segment.length * m / 10.0;
        const Vec3 p = ray.origin + (chord.span.t_exit - s / ray.direction.norm()) * ray.direction;
        worst = std::max(worst, std::abs(chord.segment(s) - cell_value(cell, p)));
      }
    }
    CHECK(worst <= CellTolerances::chord_poly_abs);
    // General rays really reach the full degree (hex20: 4, not the "2 or 3").
    CHECK(smallest_leading > 1e-6);
  }
  // Rays parallel to a brick's axis lower the degree: hex8 1, hex20 2.
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (CellType type : {CellType::hex8, CellType::hex20}) {
    std::vector<double> v(static_cast<std::size_t>(node_count(type)));
    for (double& x : v) x = u(rng);
    const HigherOrderCell cell = make_brick(type, Vec3::Zero(), I, v);
    const CellChord chord = cell_chord(cell, {Vec3(-3, 0.3, -0.2), Vec3(1, 0, 0)});
    CHECK(chord.segment.length == Approx(2.0).epsilon(1e-15));
    const auto& c = chord.segment.coeffs;
    const int expected = type == CellType::hex8 ? 1 : 2;
    for (std::size_t k = static_cast<std::size_t>(expected) + 1; k < c.size(); ++k)
      CHECK(std::abs(c[k]) <= 1e-15);
    CHECK(std::abs(c[static_cast<std::size_t>(expected)]) > 1e-3);
  }
}

TEST_CASE("cells: root splitting finds every breakpoint crossing", "[cells]") {
  // p = prod (x - r_i) with known roots; levels 0 and others.
  auto from_roots = [](const std::vector<double>& roots, double scale) {
    std::vector<double> c{scale};
    for (double r : roots) {
      std::vector<double> n(c.size() + 1, 0.0);
      for (std::size_t k = 0; k < c.size(); ++k) {
        n[k] -= r * c[k];
        n[k + 1] += c[k];
      }
      c = n;
    }
    return c;
  };
  auto near = [](const std::vector<double>& pts, double x, double tol) {
    for (double p : pts)
      if (std::abs(p - x) <= tol) return true;
    return false;
  };
  SECTION("simple roots of quadratics to quartics, with other levels") {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.05, 3.95);
    for (int n = 0; n < 300; ++n) {
      const int deg = 2 + n % 3;
      std::vector<double> roots;
      for (int i = 0; i < deg; ++i) roots.push_back(u(rng));
      std::sort(roots.begin(), roots.end());
      bool separated = true;
      for (int i = 1; i < deg; ++i) separated = separated && roots[i] - roots[i - 1] > 0.05;
      if (!separated) continue;
      const std::vector<double> c = from_roots(roots, n % 2 ? 1.0 : -2.0);
      const std::vector<double> pts = poly::split_points(c, {-1e9, 0.0, 1e9}, 4.0);
      INFO("degree " << deg);
      for (double r : roots) {
        double magnitude = 0, power = 1;
        for (double ck : c) {
          magnitude += std::abs(ck) * power;
          power *= r;
        }
        const double slope = std::abs(poly::eval(poly::derivative(c), r));
        const double tol = CellTolerances::root_ulps * 2.2e-16 * magnitude / slope + 4.4e-16 * r;
        CHECK(near(pts, r, tol));
      }
      CHECK(pts.front() == 0.0);
      CHECK(pts.back() == 4.0);
      // Between consecutive split points p has one sign and is monotone.
      for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const double m = 0.5 * (pts[i] + pts[i + 1]);
        const double q = 0.25 * pts[i] + 0.75 * pts[i + 1];
        const double pm = poly::eval(c, m), pq = poly::eval(c, q);
        CHECK(pm * pq > 0);
      }
      // The real_roots of the same polynomial agree.
      const std::vector<double> rr = poly::real_roots(c, 0.0, 4.0);
      CHECK(rr.size() == roots.size());
    }
  }
  SECTION("tangential and nearly tangential touches") {
    // (x - 1)^2 (x - 3): a double root at 1 (a critical point: always a split point, so the
    // touch is split whatever the rounding of p there), a simple one at 3.
    const std::vector<double> c = from_roots({1.0, 1.0, 3.0}, 1.0);
    const std::vector<double> pts = poly::split_points(c, {0.0}, 4.0);
    CHECK(near(pts, 1.0, 1e-12));
    CHECK(near(pts, 3.0, 1e-14));
    // (x - 1)^2 - 1e-12 (c0 = 1 - 1e-12 rounded; 1 - c0 is exact): two roots 1 -+ sqrt(1 - c0),
    // ~1e-6 from the critical point, both found to their condition (p' = 2e-6 there, p
    // evaluated to ~2 eps: 1e-10), and the critical point 1 between them.
    std::vector<double> d = from_roots({1.0, 1.0}, 1.0);
    d[0] -= 1e-12;
    const double half_gap = std::sqrt(1.0 - d[0]);
    const std::vector<double> q = poly::split_points(d, {0.0}, 2.0);
    CHECK(near(q, 1.0 - half_gap, 1e-9));
    CHECK(near(q, 1.0 + half_gap, 1e-9));
    CHECK(near(q, 1.0, 1e-15));
    CHECK(q.size() == 5);
    // (x - 1)^2 + 1e-12 does not reach 0: the critical point only.
    d[0] += 2e-12;
    const std::vector<double> r = poly::split_points(d, {0.0}, 2.0);
    CHECK(r.size() == 3);
    // An exact touch at a breakpoint: (x - 1)^2 at level 0 on [0, 2].
    const std::vector<double> e = poly::split_points(from_roots({1.0, 1.0}, 1.0), {0.0}, 2.0);
    CHECK(e == std::vector<double>{0.0, 1.0, 2.0});
  }
  SECTION("the same algorithm in 50 digits") {
    const std::vector<Real> c{Real(-2), Real(0), Real(1)};  // x^2 - 2
    const std::vector<Real> pts = poly::split_points(c, std::vector<Real>{Real(0)}, Real(2));
    REQUIRE(pts.size() == 3);  // 0 (critical point and end), sqrt 2, 2
    CHECK(static_cast<double>(abs(pts[1] - sqrt(Real(2)))) < 1e-48);
  }
}

TEST_CASE("cells: polynomial reference against hand-derived integrals", "[cells]") {
  using test::constant;
  using test::line;
  using test::uniform_tf;
  const Rgb bg{0.3, 0.3, 0.3};
  SECTION("quadratic scalar crossing a density breakpoint, constant kappa") {
    // f(s) = s^2 on [0, 2]; rho = f up to f = 1, then 1. T = 1/3 + 1; I = bg e^-T + k (1 - e^-T).
    PiecewiseLinear rho{{0.0, 1.0}, {0.0, 1.0}};
    const TransferFunctions tf = uniform_tf(rho, constant(0.7));
    const PolyRay ray{bg, {{2.0, {0.0, 0.0, 1.0}}}};
    const Real T = Real(4) / 3;
    check_reference(reference_poly_ray(tf, ray), Real(0.3) * exp(-T) + Real(0.7) * (1 - exp(-T)));
  }
  SECTION("quartic scalar crossing a breakpoint") {
    // f(s) = s^4 on [0, 2]: T = 1/5 + 1.
    PiecewiseLinear rho{{0.0, 1.0}, {0.0, 1.0}};
    const TransferFunctions tf = uniform_tf(rho, constant(0.7));
    const PolyRay ray{bg, {{2.0, {0.0, 0.0, 0.0, 0.0, 1.0}}}};
    const Real T = Real(6) / 5;
    check_reference(reference_poly_ray(tf, ray), Real(0.3) * exp(-T) + Real(0.7) * (1 - exp(-T)));
  }
  SECTION("tangential touch of a breakpoint") {
    // f(s) = (s - 1)^2 on [0, 2] touches the breakpoint 0 at s = 1; rho = f on [0, 1]: T = 2/3.
    PiecewiseLinear rho{{0.0, 1.0}, {0.0, 1.0}};
    const TransferFunctions tf = uniform_tf(rho, constant(0.7));
    const PolyRay ray{bg, {{2.0, {1.0, -2.0, 1.0}}}};
    const Real T = Real(2) / 3;
    check_reference(reference_poly_ray(tf, ray), Real(0.3) * exp(-T) + Real(0.7) * (1 - exp(-T)));
  }
  SECTION("constant rho, kappa quadratic along the ray (orientation)") {
    // kappa(f) = f on [0, 20], f(s) = 1 + 2 s + 3 s^2 (s from the far end), L = 1.5, rho = 0.8:
    // emission = int_0^L kappa(f(s)) rho e^{-rho (L - s)} ds; with u = L - s,
    // f = a0 + a1 u + a2 u^2 (a0 = f(L), a1 = -f'(L), a2 = 3) and
    // int_0^L u^m rho e^{-rho u} du = m!/rho^m (1 - e^{-rho L} sum_{j<=m} (rho L)^j / j!).
    const TransferFunctions tf = uniform_tf(constant(0.8), line(0.0, 0.0, 20.0, 20.0));  // f <= 10.75
    const PolyRay ray{bg, {{1.5, {1.0, 2.0, 3.0}}}};
    const Real L = Real(3) / 2, rho = Real(0.8);  // the double 0.8, as the transfer function holds it
    const Real a0 = 1 + 2 * L + 3 * L * L, a1 = -(2 + 6 * L), a2 = 3;
    auto moment = [&](int m) {
      Real partial = 0, term = 1;
      for (int j = 0; j <= m; ++j) {
        partial += term;
        term *= rho * L / (j + 1);
      }
      return boost::math::factorial<Real>(static_cast<unsigned>(m)) / pow(rho, m) *
             (1 - exp(-rho * L) * partial);
    };
    const Real emission = a0 * moment(0) + a1 * moment(1) + a2 * moment(2);
    check_reference(reference_poly_ray(tf, ray), Real(0.3) * exp(-rho * L) + emission);
  }
  SECTION("linear scalars: the same as the linear reference") {
    for (std::uint64_t k = 0; k < 10; ++k) {
      const TransferFunctions tf = random_transfer_functions(k);
      std::mt19937_64 rng(k);
      std::uniform_real_distribution<double> u(-0.2, 1.2);
      Ray linear{bg, {}};
      PolyRay poly{bg, {}};
      for (int s = 0; s < 3; ++s) {
        const double L = 0.3 + u(rng), f0 = u(rng), f1 = u(rng);
        linear.segments.push_back({L, f0, f1});
        poly.segments.push_back({L, {f0, (f1 - f0) / L}});
      }
      const ReferenceRay a = reference_ray(tf, linear), b = reference_poly_ray(tf, poly);
      for (int c = 0; c < 3; ++c) {
        // (f1 - f0) / L rounds: the polynomial's scalar at s = L differs from f1 by an ulp, so the
        // two rays differ by ~1e-16 relative; compare to that, and both to their bounds.
        CHECK(rel(hand_value(b.intensity[c]), hand_value(a.intensity[c])) <= 1e-14);
      }
    }
    // Exactly representable slope: agreement to the references' own accuracy.
    const TransferFunctions tf = random_transfer_functions(42);
    const Ray linear{bg, {{2.0, 0.0, 1.0}, {0.5, 1.0, 0.75}}};
    const PolyRay poly{bg, {{2.0, {0.0, 0.5}}, {0.5, {1.0, -0.5}}}};
    const ReferenceRay a = reference_ray(tf, linear), b = reference_poly_ray(tf, poly);
    for (int c = 0; c < 3; ++c)
      CHECK(rel(hand_value(b.intensity[c]), hand_value(a.intensity[c])) <= test::Tolerances::reference_rel);
  }
}

TEST_CASE("cells: the polynomial ODE is within its tolerance of the reference", "[cells]") {
  double worst = 0.0;
  for (CellType type : {CellType::tet10, CellType::hex8, CellType::hex20})
    for (std::uint64_t k = 0; k < 10; ++k) {
      const HigherOrderCell cell = random_cell(type, 300 + k);
      const TransferFunctions tf = random_transfer_functions(400 + k);
      for (std::uint64_t r = 0; r < 2; ++r) {
        const PolyRay ray = cell_poly_ray(cell, random_ray_through(cell, 500 + 2 * k + r), {0.2, 0.5, 0.8});
        const ReferenceRay ref = reference_poly_ray(tf, ray);
        for (double rtol : {1e-6, 1e-10}) {
          OdeOptions o;
          o.rtol = rtol;
          const RayResult got = PolyOdeIntegrator(tf, o).integrate(ray, nullptr);
          for (int c = 0; c < 3; ++c)
            worst = std::max(worst, relative_error(got.intensity[c], ref.intensity[c]) / rtol);
        }
      }
    }
  INFO("worst error / rtol " << worst);
  CHECK(worst <= CellTolerances::ode_per_rtol);
}

TEST_CASE("cells: hex8 at level 1 is the voxel grid of its 8 nodes", "[cells]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> v(8);
  for (double& x : v) x = u(rng);
  const HigherOrderCell cell = make_brick(CellType::hex8, Vec3(1, 1, 1), Eigen::Matrix3d::Identity(), v);
  // VTK hex order -> x-fastest grid order.
  const std::vector<double> grid_values{v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]};
  const VoxelGrid grid({2, 2, 2}, Vec3::Zero(), Vec3::Constant(2.0), grid_values);
  const TransferFunctions tf = random_transfer_functions(7);
  const ExactIntegrator exact(tf);
  for (int n = 0; n < 20; ++n) {
    const ViewRay ray = random_ray_through(cell, 600 + static_cast<std::uint64_t>(n));
    const RayResult a = exact.integrate(decomposed_ray(cell, ray, 1, {0.1, 0.1, 0.1}), nullptr);
    const RayResult b = exact.integrate(ray_segments(grid, ray, {0.1, 0.1, 0.1}), nullptr);
    for (int c = 0; c < 3; ++c) CHECK(a.intensity[c] == Approx(b.intensity[c]).epsilon(1e-13));
  }
}

TEST_CASE("cells: decomposed chords tile the cell chord", "[cells]") {
  for (CellType type : {CellType::tet10, CellType::hex8, CellType::hex20})
    for (int level : {1, 2, 4, 8}) {
      const HigherOrderCell cell = random_cell(type, 700);
      const ViewRay ray = random_ray_through(cell, 701);
      const CellChord chord = cell_chord(cell, ray);
      const Ray r = decomposed_ray(cell, ray, level, {});
      double total = 0;
      for (const auto& s : r.segments) total += s.length;
      CHECK(total == Approx(chord.segment.length).epsilon(1e-14));
      CHECK(!r.segments.empty());
      for (const auto& s : r.segments) CHECK((std::isfinite(s.scalar_far) && std::isfinite(s.scalar_exit)));
    }
}

TEST_CASE("cells: decomposition error falls at order 2 with the subdivision level", "[cells]") {
  CellsStudyOptions o;
  o.count = 12;
  o.rays_per_cell = 2;
  o.seed = 1;
  o.levels = {1, 2, 4, 8};
  o.voxel_sizes = {4, 8};
  o.voxel_rays = 6;
  const CellsReport r = run_cells_study(o);
  for (const auto& c : r.cells) {
    INFO(c.type << ": order (median fit) " << c.order_median << ", median at level 8 "
                << c.levels.back().rel.median << ", ode max " << c.ode_rel.max);
    CHECK(std::abs(c.order_median - 2.0) <= CellTolerances::order_band);
    // The error falls at every doubling (median).
    for (std::size_t l = 0; l + 1 < c.levels.size(); ++l)
      CHECK(c.levels[l + 1].rel.median < c.levels[l].rel.median);
    CHECK(c.ode_rel.max <= CellTolerances::ode_per_rtol * o.ode_rtol);
    CHECK(c.max_reference_bound_rel <= test::Tolerances::reference_rel);
  }
  // Voxel grids: Kuhn vs trilinear on the smooth field falls with the grid spacing.
  REQUIRE(r.voxels.size() == 3);
  CHECK(r.voxels[2].rel.median < r.voxels[1].rel.median);
}

TEST_CASE("cells: bad options to rayint cells", "[cells][cli]") {
  test::TempDir dir;
  for (const std::string args : {"cells --count 0 -o out.json", "cells --levels 0 -o out.json",
                                 "cells --seed -1 -o out.json", "cells --voxel-sizes 1 -o out.json",
                                 "cells --bogus -o out.json"}) {
    INFO(args);
    const test::CliRun run = test::run_cli(dir.path, args);
    CHECK(run.status == 2);
    CHECK(run.out.empty());
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(dir.entries().empty());
  }
  const test::CliRun ok = test::run_cli(dir.path, "cells --count 2 --rays 1 --levels 1,2 --voxel-sizes 3 --voxel-rays 2 -q -o out.json");
  CHECK(ok.status == 0);
  CHECK(dir.entries() == std::set<std::string>{"out.json"});
  const auto j = nlohmann::json::parse(test::slurp(dir.path / "out.json"));
  CHECK(j["cells"].size() == 3);
  CHECK(j["cells"][0]["levels"].size() == 2);
}
