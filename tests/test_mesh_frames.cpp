// Meshes far from the origin or far from unit size (issue 33, round 20), tag [mesh][frames].
// The boundary ray tracer (Embree) works in single precision. Before its local frame
// (mesh/embree_ray.hpp: the points moved to their box centre and scaled by a power of two), a
// float copy of a mesh at coordinates 1e7 x its size (a mesh in geographic coordinates), or of one
// scaled by 1e-20 or 1e15, lost its faces: every ray missed, and `rayint eval` reported the
// background with an error of 0 against a reference that took the same missing segments.
// Metamorphic checks: the same mesh and rays moved by an offset or scaled by a factor give the
// same crossings, lengths scaled by the factor, within the rounding of the moved coordinates
// themselves; rays that hit the unit mesh must hit the moved one (each transform's hit count is
// asserted, so a tracer that misses everything fails). Both traversals: tetrahedra (TetTraversal)
// and cells in their own interpolation (CellTraversal, on a gmsh-written hexahedral mesh).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/mesh/tet_traversal.hpp"

using namespace rayint;

namespace {

struct Transform {
  double scale = 1.0;
  double offset = 0.0;  // added to every coordinate after scaling
  Vec3 apply(const Vec3& p) const { return p * scale + Vec3::Constant(offset); }
  // The rounding of a moved coordinate, relative to the mesh size (~2): what the moved mesh's own
  // input loses, and so what the comparison must allow.
  double tolerance() const { return 1e-11 + 64.0 * std::numeric_limits<double>::epsilon() * std::fabs(offset) / scale; }
};

// From kMinMeshExtent (1e-60, below which a mesh is refused) to near the largest coordinate taken
// (1e18). Measured margin below the limit when written: the tet traversal passed at 1e-80 too, the
// cell traversal at 1e-75 (at 1e-80 it lost one of 112 hits).
const std::vector<Transform> kTransforms = {
    {1e-60, 0.0}, {1e-50, 0.0}, {1e-25, 0.0}, {1e-20, 0.0}, {1e-10, 0.0}, {1e10, 0.0}, {1e15, 0.0},
    {1e17, 0.0},  {1.0, 1e3},   {1.0, 1e6},   {1.0, 1e7},   {1.0, 1e9},   {1e-3, 5e3}, {1e3, -2e9},
};

// Rays from outside the unit mesh's box toward random points within radius 1.2 (some miss).
std::vector<ViewRay> sample_rays(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<ViewRay> rays;
  while (static_cast<int>(rays.size()) < n) {
    Vec3 from(u(rng), u(rng), u(rng)), to(u(rng), u(rng), u(rng));
    if (from.norm() > 1.0 || to.norm() > 1.0) continue;
    from = from.normalized() * 3.5;
    to *= 1.2;
    rays.push_back({from, (to - from).normalized()});
  }
  return rays;
}

struct Traced {
  double length = 0.0;    // total crossed length
  double weighted = 0.0;  // sum of length x mean scalar (tets): a mismatched cell changes it
};

// Each transform of `unit` against `unit` itself: every ray's length and weighted length within
// the transform's tolerance times `slack`, and as many rays hitting. Traversal is TetTraversal or
// CellTraversal; trace(traversal, transform, ray) gives the Traced of one ray, lengths in the
// unit mesh's units.
template <class Traversal, class Mesh, class Trace>
void check_transforms(const Mesh& unit, const std::vector<ViewRay>& rays, Trace trace, double slack, int min_hits) {
  const Traversal base(unit);
  std::vector<Traced> want;
  int hits = 0;
  for (const ViewRay& r : rays) {
    want.push_back(trace(base, Transform{}, r));
    hits += want.back().length > 0.0;
  }
  REQUIRE(hits > min_hits);
  for (const Transform& f : kTransforms) {
    INFO("scale " << f.scale << " offset " << f.offset);
    Mesh moved = unit;
    for (Vec3& p : moved.points) p = f.apply(p);
    const Traversal m(std::move(moved));
    int moved_hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      CAPTURE(i);
      const Traced got = trace(m, f, rays[i]);
      moved_hits += got.length > 0.0;
      CHECK(std::fabs(got.length - want[i].length) <= slack * f.tolerance());
      CHECK(std::fabs(got.weighted - want[i].weighted) <= slack * f.tolerance());
    }
    CHECK(moved_hits == hits);
  }
}

}  // namespace

TEST_CASE("tet meshes moved or scaled far from unit size keep every crossing", "[mesh][frames]") {
  const auto trace = [](const TetTraversal& m, const Transform& f, const ViewRay& r) {
    RayTrace tr;
    m.trace({f.apply(r.origin), r.direction}, tr);
    Traced t;
    for (const CellCrossing& c : tr.crossings) {
      const double len = (c.t_out - c.t_in) / f.scale;
      t.length += len;
      t.weighted += len * 0.5 * (c.s_in + c.s_out);
    }
    return t;
  };
  check_transforms<TetTraversal>(generate_mesh("ball", 4, 0).mesh, sample_rays(300, 7), trace, 1.0, 150);
}

TEST_CASE("cell meshes moved or scaled far from unit size keep every chord", "[mesh][frames]") {
  // gmsh 4.8's hexahedral box (tests/fixtures/readers/cells-hex.geo), rescaled to the unit box
  // [-1, 1]^3 first so that the transforms below are relative to a size of ~2.
  CellMesh unit = read_cell_mesh_file(RAYINT_SOURCE_DIR + "/tests/fixtures/readers/cells-hex-41.msh");
  Vec3 lo = unit.points.front(), hi = lo;
  for (const Vec3& p : unit.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (Vec3& p : unit.points) p = (2.0 * (p - lo).cwiseQuotient(hi - lo)) - Vec3::Ones();
  const auto trace = [](const CellTraversal& m, const Transform& f, const ViewRay& r) {
    CellTrace tr;
    m.trace({f.apply(r.origin), r.direction}, tr);
    Traced t;
    for (const CellChordOnRay& c : tr.chords) t.length += (c.t_out - std::max(c.t_in, tr.t_eye)) / f.scale;
    return t;
  };
  // Chords of cells in their own interpolation end where a Newton iteration stops: 1e3 x slack.
  check_transforms<CellTraversal>(unit, sample_rays(120, 11), trace, 1e3, 60);
}

TEST_CASE("a mesh spanning less than 1e-60 is refused with its extent, not as overlapping", "[mesh][frames]") {
  TetMesh tiny = generate_mesh("ball", 2, 0).mesh;
  for (Vec3& p : tiny.points) p *= 1e-90;
  REQUIRE_THROWS_WITH(validate_tet_mesh_structure(tiny, "tiny.vtk"),
                      Catch::Contains("tiny.vtk: points: the points span") && Catch::Contains("below 1e-60"));
  TetMesh small = generate_mesh("ball", 2, 0).mesh;
  for (Vec3& p : small.points) p *= 1e-55;
  CHECK_NOTHROW(validate_tet_mesh_structure(small, "small.vtk"));
}
