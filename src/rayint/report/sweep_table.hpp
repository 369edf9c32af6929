#pragma once
// The text forms of `rayint bench` (studies/sweep.hpp): the progress line per reference and
// setting on stderr, and the table of the cheapest setting that reaches each error target.
#include <string>

#include "rayint/studies/own_split_bench.hpp"
#include "rayint/studies/sweep.hpp"

namespace rayint {

std::string sweep_progress_line(const SweepProgress& progress);
std::string sweep_targets_table(const SweepResult& result);
// One line per own-interpolation mesh case (studies/own_split_bench.hpp): times, own/split,
// tets, the largest difference; a "failed:" line for a case with failed rays or no split.
std::string own_split_table(const OwnSplitRun& run);

}  // namespace rayint
