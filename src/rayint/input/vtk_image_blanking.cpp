// vtkGhostType blanking of image data; the rule is in vtk_image_blanking.hpp.
#include "rayint/input/vtk_image_blanking.hpp"

#include <cmath>
#include <cstddef>

namespace rayint {
namespace {

// The vtkGhostType DataArray of a PointData / CellData element (null node if none), its flags
// with `bit` set as bytes.
std::vector<unsigned char> flagged(const vtk_xml::Document& d, pugi::xml_node parent, const std::string& field,
                                   std::size_t n, unsigned bit) {
  for (pugi::xml_node a = parent.child("DataArray"); a; a = a.next_sibling("DataArray")) {
    if (std::string(a.attribute("Name").as_string()) != "vtkGhostType") continue;
    const std::string f = field + "/DataArray[vtkGhostType]";
    if (d.components(a, f) != 1) d.fail(f, "needs 1 component");
    const std::vector<double> v = d.values(a, f, n);
    std::size_t bad = 0;
    std::vector<unsigned char> out = ghost_flags(v, bit, &bad);
    if (bad < n) d.fail(f, "value " + std::to_string(bad) + " is not a ghost flag (an integer in [0, 255])");
    return out;
  }
  return {};
}

}  // namespace

std::vector<unsigned char> ghost_flags(const std::vector<double>& v, unsigned bit, std::size_t* bad) {
  *bad = v.size();
  std::vector<unsigned char> out(v.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!(v[i] >= 0.0 && v[i] <= 255.0 && v[i] == std::floor(v[i]))) {
      *bad = i;
      return {};
    }
    out[i] = (static_cast<unsigned>(v[i]) & bit) != 0 ? 1 : 0;
    any = any || out[i] != 0;
  }
  return any ? out : std::vector<unsigned char>{};
}

ImageGhosts read_image_ghosts(const vtk_xml::Document& d, pugi::xml_node piece, const std::string& piece_field,
                              const std::array<int, 3>& dims) {
  const std::size_t points = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
                             static_cast<std::size_t>(dims[2]);
  const std::size_t cells = static_cast<std::size_t>(dims[0] - 1) * static_cast<std::size_t>(dims[1] - 1) *
                            static_cast<std::size_t>(dims[2] - 1);
  ImageGhosts g;
  g.hidden_points = flagged(d, piece.child("PointData"), piece_field + "/PointData", points, kVtkHiddenPoint);
  if (cells > 0) g.hidden_cells = flagged(d, piece.child("CellData"), piece_field + "/CellData", cells, kVtkHiddenCell);
  return g;
}

std::vector<unsigned char> hidden_cubes(const std::array<int, 3>& dims, const std::vector<unsigned char>& hidden_points,
                                        const std::vector<unsigned char>& hidden_cells) {
  if (hidden_points.empty() && hidden_cells.empty()) return {};
  const std::size_t nx = static_cast<std::size_t>(dims[0]), ny = static_cast<std::size_t>(dims[1]);
  const std::size_t cx = nx - 1, cy = ny - 1, cz = static_cast<std::size_t>(dims[2]) - 1;
  std::vector<unsigned char> out(cx * cy * cz, 0);
  bool any = false;
  for (std::size_t k = 0; k < cz; ++k)
    for (std::size_t j = 0; j < cy; ++j)
      for (std::size_t i = 0; i < cx; ++i) {
        const std::size_t c = i + cx * (j + cy * k);
        bool hidden = !hidden_cells.empty() && hidden_cells[c] != 0;
        for (std::size_t corner = 0; corner < 8 && !hidden && !hidden_points.empty(); ++corner)
          hidden = hidden_points[(i + (corner & 1)) + nx * ((j + ((corner >> 1) & 1)) + ny * (k + ((corner >> 2) & 1)))] != 0;
        out[c] = hidden ? 1 : 0;
        any = any || hidden;
      }
  return any ? out : std::vector<unsigned char>{};
}

}  // namespace rayint
