// VTK's quadratic cells (cells/quadratic_cells.hpp) against VTK 9.1 itself, tag [cells][quadratic]:
// parametric node coordinates, shape functions and derivatives at random parametric points
// (tests/fixtures/cells/vtk_quadratic_cells.json, written by scripts/cells/vtk_quadratic_fixture.py
// from vtkQuadraticTetra / vtkQuadraticHexahedron / vtkQuadraticWedge / vtkTriQuadraticHexahedron /
// vtkBiQuadraticQuadraticWedge), and the cell-type table's
// gmsh permutations against gmsh's documented edge lists ("Node ordering", gmsh reference manual).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/cells/cell_types.hpp"
#include "rayint/cells/quadratic_cells.hpp"

using namespace rayint;

namespace {
const nlohmann::json& fixture() {
  static const nlohmann::json j = nlohmann::json::parse(
      rayint::test::slurp(std::filesystem::path(RAYINT_SOURCE_DIR + "/tests/fixtures/cells/vtk_quadratic_cells.json")));
  return j;
}
}  // namespace

TEST_CASE("quadratic cells: nodes, shape functions and derivatives equal VTK's at random points", "[cells][quadratic]") {
  for (int id : {24, 25, 26, 29, 32}) {
    INFO("VTK id " << id);
    QuadraticCellType type{};
    REQUIRE(quadratic_cell_type_from_vtk(id, type));
    const auto& c = fixture()["cells"][std::to_string(id)];
    const int n = quadratic_node_count(type);
    REQUIRE(static_cast<int>(c["nodes"].size()) == n);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k)
        CHECK(quadratic_reference_nodes(type)[static_cast<std::size_t>(i)][k] == c["nodes"][static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].get<double>());
    double worst_n = 0.0, worst_d = 0.0;
    std::vector<double> N(static_cast<std::size_t>(n)), dN(3 * static_cast<std::size_t>(n));
    REQUIRE(c["samples"].size() == 10);
    for (const auto& s : c["samples"]) {
      const Vec3 p(s["p"][0].get<double>(), s["p"][1].get<double>(), s["p"][2].get<double>());
      quadratic_shape_functions(type, p, N.data());
      quadratic_shape_derivatives(type, p, dN.data());
      for (std::size_t i = 0; i < N.size(); ++i) worst_n = std::max(worst_n, std::fabs(N[i] - s["N"][i].get<double>()));
      for (std::size_t i = 0; i < dN.size(); ++i) worst_d = std::max(worst_d, std::fabs(dN[i] - s["dN"][i].get<double>()));
    }
    // Measured: N 1.8e-16 / 1.1e-15 / 4.4e-16 / 0 / 1.1e-16, dN 0 / 1.8e-15 / 5.6e-16 / 0 /
    // 8.6e-16 (tetra, hexahedron, wedge: rounding of the Vandermonde inverse; triquadratic
    // hexahedron, biquadratic-quadratic wedge: products); 1e-13 leaves >= 50x.
    CHECK(worst_n <= 1e-13);
    CHECK(worst_d <= 1e-13);
    WARN("VTK id " << id << ": worst |N - VTK| " << worst_n << ", |dN - VTK| " << worst_d << " over 10 points");
  }
}

TEST_CASE("quadratic cells: the table's gmsh permutations match gmsh's documented edge lists", "[cells][quadratic]") {
  // gmsh reference manual, "Node ordering": the mid-edge nodes of the 10-node tetrahedron,
  // 20-node hexahedron and 15-node prism, as corner pairs, after the corners (which gmsh and VTK
  // number alike); the 27-node hexahedron and 18-node prism add the centres of the faces listed
  // (as corner quadruples), the hexahedron then its centre (the mean of all 8 corners).
  struct Case {
    int vtk_id;
    std::vector<std::vector<int>> gmsh_entities;  // corner sets whose mean is the node
  };
  const std::vector<std::vector<int>> hex_edges = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                                   {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
  const std::vector<std::vector<int>> prism_edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
  std::vector<std::vector<int>> hex27 = hex_edges, prism18 = prism_edges;
  for (const std::vector<int>& f : std::vector<std::vector<int>>{
           {0, 1, 2, 3}, {0, 1, 4, 5}, {0, 3, 4, 7}, {1, 2, 5, 6}, {2, 3, 6, 7}, {4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}})
    hex27.push_back(f);
  for (const std::vector<int>& f : std::vector<std::vector<int>>{{0, 1, 3, 4}, {0, 2, 3, 5}, {1, 2, 4, 5}}) prism18.push_back(f);
  const Case cases[] = {
      {24, {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}}},
      {25, hex_edges},
      {26, prism_edges},
      {29, hex27},
      {32, prism18},
  };
  for (const Case& k : cases) {
    INFO("VTK id " << k.vtk_id);
    QuadraticCellType type{};
    REQUIRE(quadratic_cell_type_from_vtk(k.vtk_id, type));
    const std::vector<Vec3>& vtk_nodes = quadratic_reference_nodes(type);
    const int corners = static_cast<int>(vtk_nodes.size() - k.gmsh_entities.size());
    std::vector<Vec3> gmsh_nodes(vtk_nodes.begin(), vtk_nodes.begin() + corners);
    for (const auto& e : k.gmsh_entities) {
      Vec3 mean = Vec3::Zero();
      for (int i : e) mean += vtk_nodes[static_cast<std::size_t>(i)];
      gmsh_nodes.push_back(mean / static_cast<double>(e.size()));
    }
    const CellTypeInfo* row = cell_type_from_vtk(k.vtk_id);
    REQUIRE(row != nullptr);
    for (std::size_t i = 0; i < vtk_nodes.size(); ++i)
      CHECK(gmsh_nodes[static_cast<std::size_t>(row->gmsh_to_vtk[i])] == vtk_nodes[i]);
  }
}
