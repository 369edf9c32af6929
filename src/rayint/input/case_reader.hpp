#pragma once
// Reading and validating case files (format: cases/README.md). Every problem is reported as an
// InputError whose message is one line naming the file and the JSON field.
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

// `source` is the file name used in messages. Throws InputError. `mesh` applies to mesh cases
// (mesh_case_reader.hpp: reorient/drop by default, refuse with --strict-mesh); for a mesh case,
// `*repairs` (when given) receives what reading its mesh reoriented and dropped.
// A mesh case whose file holds cells other than tetrahedra (without --cells split) has no
// segments: with `own_cells` given, its MeshCase goes there (MeshCase::cells set; eval integrates
// it in the cells' own interpolation, studies/own_cells_eval.hpp; check compares a candidate with
// that, studies/check.hpp check_candidate_own) and the Case returned holds only
// its name and transfer functions; without, it is refused with one line naming the mesh file.
Case parse_case_text(std::string_view text, const std::string& source, const MeshReadOptions& mesh = {},
                     std::optional<TetRepairs>* repairs = nullptr, std::optional<MeshCase>* own_cells = nullptr);
Case read_case_file(const std::string& path, const MeshReadOptions& mesh = {},
                    std::optional<TetRepairs>* repairs = nullptr, std::optional<MeshCase>* own_cells = nullptr);

namespace detail {
// The same reading with every segment kept in the JSON tree until the schema walk (how
// parse_case_text read before it streamed segments; ~10x the text in memory). For the test that
// both give the same cases and the same messages.
Case parse_case_text_tree(std::string_view text, const std::string& source);
}  // namespace detail

// The name of the gate configuration that lives beside the cases (cases/gates.json); it is the
// one .json file in a case folder that is not a case.
inline constexpr const char* kGateConfigName = "gates.json";

// Every case file in `dir`: the *.json files except kGateConfigName, sorted by name.
// Throws InputError if `dir` cannot be listed.
std::vector<std::string> list_case_files(const std::string& dir);

}  // namespace rayint
