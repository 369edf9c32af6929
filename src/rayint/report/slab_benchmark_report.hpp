#pragma once
// The report of `rayint slab --benchmark`: per published value, each solver's value, deviation
// and verdict, then the costs and the acceptance rule (slab_benchmark.hpp); as a table or JSON.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/scattering/slab_run.hpp"

namespace rayint {

std::string slab_benchmark_table(const BenchmarkReport& report, const BenchmarkRunOptions& options);
nlohmann::json slab_benchmark_json(const SlabBenchmark& benchmark, const BenchmarkReport& report,
                                   const BenchmarkRunOptions& options);

}  // namespace rayint
