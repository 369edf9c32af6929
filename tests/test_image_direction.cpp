// VTK 9 images with a rotated Direction (issue 27): placed with world = Origin + Direction (index
// * spacing), checked against VTK's own probe of the file it wrote, and integrated along rays:
// the rotated image along a ray equals the axis-aligned image along the rotated ray, and the
// exact trilinear integral of the rotated image matches the 50-digit reference. Fixtures and the
// script that wrote them with VTK 9.1: tests/fixtures/vti-direction/.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "test_paths.hpp"
#include "rayint/core/error.hpp"
#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/input/voxel_grid_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/scene/grid_field.hpp"
#include "transfer_builders.hpp"

using namespace rayint;

namespace {

namespace fs = std::filesystem;
const fs::path kDir = fs::path(RAYINT_SOURCE_DIR) / "tests" / "fixtures" / "vti-direction";

nlohmann::json probe() {
  std::ifstream in(kDir / "probe.json");
  return nlohmann::json::parse(in);
}

TransferFunctions tf() {
  TransferFunctions t;
  t.density = {PiecewiseLinear{{0.0, 1.0, 2.5}, {0.2, 1.4, 0.6}}, PiecewiseLinear{{0.5, 1.8}, {0.3, 2.0}},
               PiecewiseLinear{{0.0, 2.5}, {1.0, 0.1}}};
  t.color = {PiecewiseLinear{{0.0, 1.5}, {0.9, 0.1}}, PiecewiseLinear{{0.8, 1.2, 2.0}, {0.2, 1.0, 0.4}},
             PiecewiseLinear{{0.0}, {0.5}}};
  return t;
}

}  // namespace

TEST_CASE("a rotated .vti is placed as VTK places it: VTK's probe values at VTK's world points",
          "[tfstep][vtkxml][grid]") {
  const nlohmann::json p = probe();
  const VoxelGrid g = read_vti((kDir / "rotated.vti").string());
  REQUIRE_FALSE(g.placement().identity());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      CHECK(g.placement().direction(r, c) == p["direction"][static_cast<std::size_t>(3 * r + c)].get<double>());
  for (int a = 0; a < 3; ++a) CHECK(g.placement().pivot[a] == p["origin"][static_cast<std::size_t>(a)].get<double>());
  const GridField field(g);
  const auto& pts = p["points"];
  const auto& want = p["f"];
  REQUIRE(pts.size() == 300);
  double worst = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3 w(pts[i][0].get<double>(), pts[i][1].get<double>(), pts[i][2].get<double>());
    const double got = field.density(w), vtk = want[i].get<double>();
    INFO("point " << i << " rayint " << got << " VTK " << vtk);
    // vtkProbeFilter locates the point with its own tolerance (parametric coordinates found
    // iteratively to ~1e-8 here); trilinear interpolation of O(1) values then agrees to that.
    CHECK(std::fabs(got - vtk) < 1e-6);
    worst = std::max(worst, std::fabs(got - vtk));
    CHECK(field.bounds().contains(w));
  }
  WARN("[tfstep] rotated .vti vs VTK 9.1's probe at 300 world points: worst |difference| " << worst);
  // The axis-aligned file of the same image has no placement, and its grid in its own frame is
  // the rotated file's.
  const VoxelGrid axis = read_vti((kDir / "axis.vti").string());
  CHECK(axis.placement().identity());
  CHECK(axis.values() == g.values());
  CHECK(axis.origin() == g.origin());
  CHECK(axis.spacing() == g.spacing());
}

TEST_CASE("rays through a rotated image integrate as the unrotated image along the rotated rays",
          "[tfstep][grid][exact]") {
  const VoxelGrid rotated = read_vti((kDir / "rotated.vti").string());
  const VoxelGrid axis = read_vti((kDir / "axis.vti").string());
  const GridField placed(rotated), plain(axis);
  const Eigen::Matrix3d d = rotated.placement().direction;
  const Vec3 pivot = rotated.placement().pivot;
  const TransferFunctions t = tf();
  const TrilinearIntegrator exact(t);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Bounds box = placed.bounds();
  const Vec3 centre = 0.5 * (box.lower + box.upper);
  double worst_same = 0.0, worst_ref = 0.0;
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    Vec3 dir(u(rng), u(rng), u(rng));
    dir.normalize();
    const Vec3 target = centre + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(0.4 * (box.upper - box.lower));
    const ViewRay world{target - 10.0 * dir, dir};
    // The same ray expressed in the image's frame, built here from the file's Direction.
    const ViewRay turned{pivot + d.transpose() * (world.origin - pivot), d.transpose() * world.direction};
    const TrilinearRayResult a = exact.integrate(placed.grid(), placed.to_grid(world), Rgb{0.1, 0.2, 0.3});
    const TrilinearRayResult b = exact.integrate(plain.grid(), turned, Rgb{0.1, 0.2, 0.3});
    if (a.pieces > 0) ++hits;
    const ReferenceRay ref =
        reference_poly_ray(t, trilinear_ray(placed.grid(), placed.to_grid(world), Rgb{0.1, 0.2, 0.3}));
    for (int c = 0; c < kChannels; ++c) {
      INFO("ray " << i << " channel " << c);
      // The same ray turned by the same matrix (Eigen may order the products differently: rounding).
      CHECK(std::fabs(a.intensity[c] - b.intensity[c]) <= 1e-13 * std::fabs(b.intensity[c]));
      CHECK(relative_error(a.intensity[c], ref.intensity[c]) < 1e-12);
      CHECK(relative_error(a.transmittance[c], ref.transmittance[c]) < 1e-12);
      worst_ref = std::max(worst_ref, relative_error(a.intensity[c], ref.intensity[c]));
      worst_same = std::max(worst_same, std::fabs(a.intensity[c] - b.intensity[c]));
    }
    // The density a sampling method reads along the world ray is the unrotated image's along the
    // turned ray.
    for (const double s : {9.0, 10.0, 10.5}) {
      const double x = placed.density(world.origin + s * world.direction);
      const double y = plain.density(turned.origin + s * turned.direction);
      CHECK(std::fabs(x - y) <= 1e-14 * (1.0 + std::fabs(y)));
    }
  }
  CHECK(hits > 150);
  WARN("[tfstep] rotated image: 200 rays (" << hits << " hit), exact vs 50-digit reference worst rel " << worst_ref
                                            << ", rotated vs unrotated-with-rotated-ray worst |diff| " << worst_same);
}

TEST_CASE("a .vti whose Direction is not orthonormal is refused with one line naming the field",
          "[tfstep][vtkxml][grid]") {
  const std::string text = R"(<?xml version="1.0"?>
<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">
  <ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1" Direction="2 0 0 0 1 0 0 0 1">
  <Piece Extent="0 1 0 1 0 1">
    <PointData Scalars="f"><DataArray type="Float64" Name="f" format="ascii">0 1 2 3 4 5 6 7</DataArray></PointData>
  </Piece>
  </ImageData>
</VTKFile>
)";
  try {
    parse_vti(text, "scaled.vti", "");
    FAIL("a scaled Direction was read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("scaled.vti: ImageData: Direction is not orthonormal") == 0);
  }
}
