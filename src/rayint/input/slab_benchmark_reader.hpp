#pragma once
// Reads a published slab benchmark file (the DISORT/Garcia-Siewert tables in
// ../shared/benchmarks/): problem groups by phase function, each problem's optical thickness,
// albedo, source and published values. Every problem is one InputError line naming the field.
#include <string>

#include "rayint/scattering/slab_benchmark.hpp"

namespace rayint {

SlabBenchmark read_slab_benchmark(const std::string& path);
SlabBenchmark parse_slab_benchmark(const std::string& text, const std::string& source);

}  // namespace rayint
