#pragma once
// The table of `rayint eval --format table`: per case and method, the largest errors over the
// rays, the reference's error estimate, the time per ray and the branches taken.
#include <string>
#include <vector>

#include "rayint/studies/evaluate.hpp"

namespace rayint {

std::string evaluation_table(const std::vector<CaseEvaluation>& cases);

}  // namespace rayint
