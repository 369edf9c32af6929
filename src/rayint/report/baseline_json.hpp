#pragma once
// Drift baseline files (studies/drift.hpp): one JSON file per method, written by
// `rayint gate --write-baseline DIR`, read back by input/baseline_reader.hpp. Numbers in the
// shortest form that reads back as the same double; NaN as null, infinities as "inf" / "-inf";
// one ray per line, so a regenerated baseline diffs line by line in review.
#include <string>

#include "rayint/studies/drift.hpp"

namespace rayint {

std::string baseline_text(const Baseline& baseline);
// The file name of a method's baseline: the label with every character outside [A-Za-z0-9._-]
// replaced by '_', plus ".json" (e.g. "riemann_n_64.json").
std::string baseline_file_name(const std::string& method);

}  // namespace rayint
