#pragma once
// table_grid.hpp -- private helper shared by the table methods (preintegrated.cpp,
// psi_table.cpp): where a coordinate falls on a uniform grid of n points, for the three ways
// the tables are read.
//   nearest: the closest grid point (ties round up), weight 0.
//   linear:  the cell [i, i+1] holding the coordinate and the weight w of point i+1
//            (value = (1 - w) v_i + w v_{i+1}); bilinear/trilinear is this per axis.
//   floor:   VTK's indexing in vtkUnstructuredGridPartialPreIntegration::Psi(): index
//            floor(x), weight 0 (a one-sided "nearest" whose error has a sign).
// Coordinates are in grid units (0 .. n-1) and are clamped to the grid first, so a lookup
// never reads outside the table; callers count clamps themselves where that is an error.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/integrators/integrator.hpp"

namespace rayint::table {

enum class Lookup { nearest, linear, floor };

inline const char* lookup_name(Lookup l) {
  switch (l) {
    case Lookup::nearest: return "nearest";
    case Lookup::linear: return "linear";
    case Lookup::floor: return "floor";
  }
  return "?";
}

// Reads spec's "lookup" parameter; `allow_floor` admits VTK's floor indexing.
// The lookup parameter of a validated spec (its choices are in the method table, registry.cpp).
inline Lookup parse_lookup(const MethodSpec& spec) {
  const std::string text = spec.text("lookup");
  if (text == "nearest") return Lookup::nearest;
  if (text == "floor") return Lookup::floor;
  return Lookup::linear;
}

struct GridCoord {
  int i = 0;       // lower (or only) grid point
  double w = 0.0;  // weight of point i + 1; 0 for nearest/floor
};

// `x` in grid units; NaN is treated as 0 (it cannot arise from finite inputs).
inline GridCoord locate(double x, int n, Lookup lookup) {
  const double top = n - 1;
  if (!(x > 0.0)) x = 0.0;
  if (x > top) x = top;
  GridCoord g;
  switch (lookup) {
    case Lookup::nearest:
      g.i = static_cast<int>(std::floor(x + 0.5));
      break;
    case Lookup::floor:
      g.i = static_cast<int>(std::floor(x));
      break;
    case Lookup::linear: {
      const double f = std::floor(x);
      g.i = std::min(static_cast<int>(f), n - 2);
      g.w = x - g.i;
      break;
    }
  }
  return g;
}

// Bilinear read of a row-major n x n array (first index = row) at (r, c); nearest/floor read
// one entry (their weights are 0, and index + 1 is not touched then).
inline double bilerp(const double* v, int n, const GridCoord& r, const GridCoord& c) {
  const std::size_t base = static_cast<std::size_t>(r.i) * n + c.i;
  if (r.w == 0.0 && c.w == 0.0) return v[base];
  const double top = c.w == 0.0 ? v[base] : (1.0 - c.w) * v[base] + c.w * v[base + 1];
  if (r.w == 0.0) return top;
  const std::size_t below = base + static_cast<std::size_t>(n);
  const double bottom =
      c.w == 0.0 ? v[below] : (1.0 - c.w) * v[below] + c.w * v[below + 1];
  return (1.0 - r.w) * top + r.w * bottom;
}

}  // namespace rayint::table
