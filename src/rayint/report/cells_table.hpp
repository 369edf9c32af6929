#pragma once
// The table of `rayint cells`: per cell type, the error of each subdivision level and of the ODE,
// the fitted order and the reference's cost; then the voxel grids (studies/cells_study.hpp).
#include <string>

#include "rayint/studies/cells_study.hpp"

namespace rayint {

std::string cells_table(const CellsReport& report);

}  // namespace rayint
