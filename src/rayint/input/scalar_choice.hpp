#pragma once
// Which array of a mesh file is the field to integrate, as every mesh reader takes it (a mesh
// case's "scalar_field" and "cell_data", `rayint mesh info --array/--point-average`).
#include <string>

namespace rayint {

struct ScalarChoice {
  // The array of that name; "" = the reader's rule (the file's active scalars, else its first
  // one-component array that is not a region marker; input/mesh_assembly.hpp).
  std::string name;
  // A cell field becomes point data averaged as ParaView's Cell Data to Point Data
  // (cell_to_point_average); false: it stays constant per cell ("cell_data": "constant").
  bool cell_to_point = false;
};

}  // namespace rayint
