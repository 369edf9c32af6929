// rayint mesh info FILE [--check] -- what a mesh file holds as rayint reads it (report/mesh_info.hpp):
// bounds, cells by type (kept / skipped), arrays and which is the scalar, orientation counts;
// --check also looks for overlapping tetrahedra (mesh/mesh_check.hpp) and exits 1 naming two of
// them when it finds some. Bad input: one line, exit 2.
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/mesh/mesh_check.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/report/mesh_info.hpp"

namespace rayint::cli {

void set_mesh_command(CLI::App& app) {
  struct Options {
    std::string file, format = "text", output;
    ScalarChoice scalar;  // --array, --point-average
    bool check = false, quick = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* mesh = app.add_subcommand("mesh", "Mesh files as rayint reads them");
  mesh->require_subcommand(1);
  CLI::App* cmd = mesh->add_subcommand("info", "Bounds, cells by type, arrays, the scalar, orientation (--check: overlaps)");
  cmd->add_option("file", opt->file, "A mesh file: .vtk, .vtu, .pvtu, .msh, .ele, .vts, .vtr, .pvts, .pvtr, .vti (an image as its voxels)")->required();
  cmd->add_option("--array", opt->scalar.name, "The array to take as the scalar (default: the rule of docs/meshes.md)");
  cmd->add_flag("--point-average", opt->scalar.cell_to_point, "A cell field becomes point data as ParaView's Cell Data to Point Data");
  cmd->add_flag("--check", opt->check, "Look for overlapping tetrahedra, every candidate pair (exit 1 naming two when found)");
  cmd->add_flag("--quick-check", opt->quick, "The check a mesh case runs on load: only pairs that share no point");
  cmd->add_option("--format", opt->format, "text or json")->check(CLI::IsMember({"text", "json"}));
  add_output_option(cmd, opt->output);
  cmd->callback([opt] {
    // Read as cells: a file of tetrahedra only continues as before; one with hexahedra, wedges,
    // pyramids or voxels is reported by type (it has no tetrahedra to check for overlaps).
    // Quadratic tetrahedra are not cells of the CellMesh path (--cells split refuses them): a
    // file the cell reader refuses is read again by the tetrahedral path, which keeps them; when
    // that refuses it too, the cell reader's line stands.
    CellMesh cells;
    std::optional<TetMesh> quadratic;
    try {
      cells = read_cell_mesh_file(opt->file, opt->scalar);
    } catch (const InputError& cell_error) {
      if (std::string(cell_error.what()).find("quadratic tetra (VTK id 24)") == std::string::npos) throw;
      quadratic = read_mesh_file(opt->file, opt->scalar);  // its own line if it refuses
    }
    // The cell readers keep quadratic tetrahedra as cells (curved ones are integrated there); a
    // file of tetrahedra and tet10 only is reported by the tetrahedral reading, which says
    // whether the edges are straight.
    if (!quadratic) {
      bool tets = true, tet10 = false;
      for (MeshCellType t : cells.types) {
        tets = tets && (t == MeshCellType::tetra || t == MeshCellType::quadratic_tetra);
        tet10 = tet10 || t == MeshCellType::quadratic_tetra;
      }
      if (tets && tet10) quadratic = read_mesh_file(opt->file, opt->scalar);
    }
    MeshInfo info;
    info.file = opt->file;
    if (!quadratic && !cells.only_tets()) {
      info.cells = &cells;
      emit(opt->format == "json" ? to_json(info).dump(2) + "\n" : to_text(info), opt->output);
      return;
    }
    const TetMesh m = quadratic ? std::move(*quadratic) : take_tets(std::move(cells));
    info.mesh = &m;
    info.orientation = orientation_counts(m);
    if (!m.edge_nodes.empty()) info.tet10 = check_tet10_edges(m);
    if (opt->check || opt->quick) {
      const auto t0 = std::chrono::steady_clock::now();
      // As on load: the face adjacency, then the boundary fast path
      // (mesh_check.hpp), when its premises hold: no degenerate tet, and faces that the
      // traversal accepts (otherwise the full check decides, as it does when the fast path
      // finds anything).
      TetNeighbors next;
      if (info.orientation.zero_volume == 0 && info.orientation.slivers == 0) {
        try {
          next = tet_neighbors(m, opt->file);
        } catch (const InputError&) {
          next.clear();
        }
      }
      info.overlap = find_overlapping_tets(m, next, opt->check ? OverlapScope::all_pairs : OverlapScope::disjoint_pairs);
      info.check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      info.checked = true;
    }
    emit(opt->format == "json" ? to_json(info).dump(2) + "\n" : to_text(info), opt->output);
    if (info.overlap) {
      std::cerr << "rayint: mesh info: " << opt->file << ": tetrahedra overlap (cells "
                << (m.info.cell_ids.size() == m.tets.size() ? m.info.cell_ids[info.overlap->first] : static_cast<long long>(info.overlap->first))
                << " and "
                << (m.info.cell_ids.size() == m.tets.size() ? m.info.cell_ids[info.overlap->second] : static_cast<long long>(info.overlap->second))
                << " of the file)\n";
      throw ChecksFailed{};
    }
  });
}

}  // namespace rayint::cli
