// full_pivot_lu_solve (mesh/tet_cell.hpp) against Eigen's own FullPivLU, bit for bit: the
// written-out version must give the doubles Eigen gives, so renders stay cmp-identical.
#include <Eigen/LU>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "rayint/mesh/tet_cell.hpp"

namespace {

// 0 when the two solutions are the same bits (signed zeros included), else 1.
int differs(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d eigen = a.fullPivLu().solve(b);
  const rayint::Vec3 ours = rayint::full_pivot_lu_solve(a, b);
  return std::memcmp(eigen.data(), ours.data(), 3 * sizeof(double)) == 0 ? 0 : 1;
}

}  // namespace

TEST_CASE("full_pivot_lu_solve: Eigen's FullPivLU solve bit for bit", "[mesh][lu]") {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> small(-2, 2);
  std::uniform_real_distribution<double> exponent(-150.0, 150.0);
  const auto random_matrix = [&] {
    Eigen::Matrix3d a;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a(i, j) = u(rng);
    return a;
  };
  const auto random_vector = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  long failures = 0, cases = 0;
  const auto check = [&](const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
    failures += differs(a, b);
    ++cases;
  };
  SECTION("random systems, also scaled by 1e-150 to 1e150") {
    for (int n = 0; n < 200000; ++n) {
      const double scale = n % 2 == 0 ? 1.0 : std::pow(10.0, exponent(rng));
      check(scale * random_matrix(), random_vector());
    }
  }
  SECTION("integer entries (ties between pivot candidates), zeros in the right-hand side") {
    for (int n = 0; n < 200000; ++n) {
      Eigen::Matrix3d a;
      Eigen::Vector3d b;
      for (int i = 0; i < 3; ++i) {
        b[i] = small(rng);
        for (int j = 0; j < 3; ++j) a(i, j) = small(rng);
      }
      check(a, b);
    }
  }
  SECTION("rank 2, 1 and 0, and nearly singular systems") {
    for (int n = 0; n < 100000; ++n) {
      Eigen::Matrix3d a = random_matrix();
      const int kind = n % 4;
      if (kind == 0) a.row(2) = 0.3 * a.row(0) - 1.7 * a.row(1);                 // rank 2 (up to rounding)
      if (kind == 1) a.row(1) = a.row(2) = a.row(0) * u(rng);                    // rank 1
      if (kind == 2) a.row(2) = a.row(0) + 1e-13 * Eigen::RowVector3d(u(rng), u(rng), u(rng));  // a sliver
      if (kind == 3 && n % 8 == 3) a.setZero();                                  // rank 0
      check(a, random_vector());
    }
    check(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    check(Eigen::Matrix3d::Zero(), Eigen::Vector3d(1, 2, 3));
  }
  SECTION("edges of tetrahedra as fit_linear_tet builds them") {
    for (int n = 0; n < 100000; ++n) {
      std::array<rayint::Vec3, 4> x;
      std::array<double, 4> s{};
      for (std::size_t k = 0; k < 4; ++k) {
        x[k] = rayint::Vec3(u(rng), u(rng), u(rng)) * (n % 3 == 0 ? 1e-3 : 10.0);
        s[k] = u(rng);
      }
      Eigen::Matrix3d edges;
      Eigen::Vector3d rhs;
      for (int k = 0; k < 3; ++k) {
        edges.row(k) = (x[static_cast<std::size_t>(k + 1)] - x[0]).transpose();
        rhs[k] = s[static_cast<std::size_t>(k + 1)] - s[0];
      }
      check(edges, rhs);
      const rayint::Vec3 g = rayint::fit_linear_tet(x, s).gradient;
      const Eigen::Vector3d eigen = edges.fullPivLu().solve(rhs);
      failures += std::memcmp(eigen.data(), g.data(), 3 * sizeof(double)) == 0 ? 0 : 1;
    }
  }
  INFO(std::to_string(failures) + " of " + std::to_string(cases) + " systems differ from Eigen's solve");
  CHECK(cases > 0);
  CHECK(failures == 0);
}
