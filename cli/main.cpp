// rayint -- numerical verification of the ray integrals of direct volume rendering.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "commands.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "shard.hpp"
#ifdef RAYINT_WITH_VTK
#include "rayint/vtk/vtk_integrators.hpp"
#include "rayint/vtk/vtk_mesh_reader.hpp"
#endif
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/effects/standard_effects.hpp"

namespace rayint::cli {

void emit(const std::string& text, const std::string& path) {
  if (path.empty() || path == "-") {
    std::cout << text;
    if (!text.empty() && text.back() != '\n') std::cout << '\n';
  } else {
    write_file_atomically(path, (text.empty() || text.back() == '\n') ? text : text + "\n");
  }
}

std::vector<MethodSpec> parse_methods_option(const std::string& csv, const std::string& option) {
  try {
    return parse_method_list(csv);
  } catch (const MethodSpecError& e) {
    throw MethodSpecError(option + " " + e.what());
  }
}

// Every subcommand, by name, with the function that registers it on an app.
struct SubcommandEntry {
  const char* name;
  void (*set)(CLI::App& app);
};

void build_app(CLI::App& app);

const SubcommandEntry kSubcommands[] = {
    {"eval", set_eval_command},
    {"bench", set_bench_command},
    {"stress", set_stress_command},
    {"gate", set_gate_command},
    {"check", set_check_command},
    {"render", set_render_command},
    {"scene-sweep", set_scene_sweep_command},
    {"converge", set_converge_command},
    {"generate-mesh", set_generate_mesh_command},
    {"mesh", set_mesh_command},
    {"mesh-agreement", set_mesh_agreement_command},
    {"cells", set_cells_command},
    {"slab", set_slab_command},
    {"scatter", set_scatter_command},
    {"tf", set_tf_command},
    {"methods", set_methods_command},
    {"grad", set_grad_command},
    {"gradcheck", set_gradcheck_command},
    {"merge", [](CLI::App& app) { set_merge_command(app, build_app); }},
};

// Every subcommand on `app` (main's app, and the app `rayint merge` replays a run on).
void build_app(CLI::App& app) {
  for (const SubcommandEntry& s : kSubcommands) s.set(app);
}

// The subcommand named `first` (main's argv[1]) alone when there is one by that name, else every
// subcommand (the usage, --help, --version, a misspelt name: CLI11 lists them all). Registering
// the 19 subcommands' options, and main's two passes over them, cost ~1.8 ms CPU of each run's
// start-up (`rayint render /nonexistent.json -o x.png`: 23.3 -> 21.3 ms CPU, 485 -> 425 faults;
// issue 33).
void build_app_for(CLI::App& app, const char* first) {
  for (const SubcommandEntry& s : kSubcommands) {
    if (first != nullptr && std::strcmp(first, s.name) == 0) return s.set(app);
  }
  build_app(app);
}

}  // namespace rayint::cli

namespace {

// Every byte of stdout is checked: a full disk or a closed reader is an error, not success.
// Returns false (after one line on stderr) when stdout could not be written completely.
bool flush_stdout() {
  std::cout.flush();
  const bool ok = !std::cout.fail() && std::fflush(stdout) == 0;
  const int err = errno;
  if (!ok) std::cerr << "rayint: error: standard output: cannot write (" << std::strerror(err) << ")\n";
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // A fixed mmap threshold instead of glibc's dynamic one: once a large block is freed glibc
  // raises the threshold up to 32 MiB, and later blocks below it come from the heap, which keeps
  // them resident after free. Loading a big mesh frees several such blocks (the file, the face
  // records): measured on the 1.05M-tet ball, the render's peak RSS falls from 243 to 210 MB (.vtk;
  // issue 33, reports/scaling/NOTES.md). 1 MiB, PrefaultedAllocator's bound (core/prefaulted.hpp:
  // larger arrays are mapped there): with glibc's 128 KiB a block that did not fit in the heap's
  // free top was mapped instead of growing the heap by M_TOP_PAD (below), so whether the loaders'
  // sub-MiB arrays were reused depended on whether the heap had grown before them (105k-tet .vtu
  // load: 4,400 minor faults with one subcommand registered at start-up, 3,500 with all, 3,500
  // with 1 MiB either way; render 512 x 512 peak RSS 46,300 KiB at 105k, 220,300 KiB at 1.05M).
  mallopt(M_MMAP_THRESHOLD, 1024 * 1024);
  // Heap growth in steps of 16 MiB (M_TOP_PAD; glibc's default 128 KiB) and no trim below 64 MiB
  // of free top (M_TRIM_THRESHOLD; default 128 KiB). A request that fits in the heap's free top is
  // carved from it without an mmap, whatever its size, so the loaders' temporaries below a few MiB
  // (the points, offsets and types arrays, the face keys, ...) come from the heap and, once freed,
  // their pages are reused by the next ones instead of being unmapped and faulted in afresh (each
  // first touch of a 4 KiB page costs ~8 us on the Zen 5 VM). Blocks of at least the mmap
  // threshold that do not fit in the free top are still mapped. Issue 33, 105k-tet ball, with
  // M_ARENA_MAX below and the malloc_trim after the render (render_mesh.cpp): load (`render`
  // 16 x 16, scripts/load_ab.py) .vtk/.vtu/.msh 126.8/139.5/141.1 -> 114.6/122.9/118.5 ms CPU
  // (0.90/0.88/0.84; with the 1 MiB threshold above: 0.83/0.84/0.80), minor faults
  // 3,895/4,948/4,792 -> 2,918/3,428/2,731; render 512 x 512 peak RSS (/usr/bin/time %M)
  // 47,100 -> 46,800 KiB (105k), 221,000 -> 220,700 KiB (1.05M), same images.
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  // One arena for every thread: the render's worker threads then take their buffers from the
  // main heap's free space (the load's freed temporaries) instead of a fresh per-thread heap, and
  // malloc_trim (render_mesh.cpp, after the render) can return them: a thread heap's free top is
  // kept at M_TOP_PAD and malloc_trim does not trim it (glibc 2.36). Small blocks come from each
  // thread's tcache without the arena's lock.
  mallopt(M_ARENA_MAX, 1);
#endif
  rayint::remove_temporaries_on_signals();  // no out.npy.tmp.<pid> left by Ctrl-C or a kill
  rayint::register_standard_effects();  // multiple_scattering (scene/effect.hpp)
#ifdef RAYINT_WITH_VTK
  rayint::register_vtk_methods();  // vtk_linear, vtk_partial_preint, vtk_preint, vtk_homogeneous
  rayint::register_vtk_mesh_readers();  // mesh_file .vtu, .pvtu
#endif
  CLI::App app{"rayint: how far is a ray integration from the truth, and what does it cost"};
  app.require_subcommand(0, 1);  // none: the usage (below), exit 2
  app.set_version_flag("--version", std::string("rayint ") + RAYINT_VERSION);
  app.footer("Exit codes: 0 ok; 1 a check, gate or method failed (output written, failures "
             "marked); 2 bad input or usage (docs/exit-codes.md).");
  rayint::cli::build_app_for(app, argc > 1 ? argv[1] : nullptr);
  rayint::cli::accept_integer_float_forms(app);  // --photons 1e6 (cli/options.hpp)
  rayint::cli::check_number_options(app);         // --exposure nan, -1 (cli/options.hpp)
  for (int i = 2; i < argc; ++i) rayint::cli::shard_context().args.push_back(argv[i]);
  // A command's outputs (-o, --stats, --junit, artifacts, ...) land together or not at all:
  // each is staged beside its target and renamed when the command has finished.
  int status = 0;
  try {
    rayint::OutputBatch outputs;
    try {
      app.parse(argc, argv);
    } catch (const rayint::cli::ChecksFailed&) {
      status = rayint::cli::kExitFailed;  // the report of the failure is still written
    }
    outputs.commit();
    rayint::cli::HeldLines::instance().release();  // input lines no progress update printed
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const std::bad_alloc&) {  // a limit of the machine (ulimit -v), not of rayint's own
    std::cout.flush();
    if (rayint::cli::progress_line_open()) std::cerr << '\n';
    std::cerr << "rayint: error: out of memory (std::bad_alloc); docs/limits.md lists the sizes rayint checks\n";
    return rayint::cli::kExitBadInput;
  } catch (const std::exception& e) {  // CLI::ParseError, InputError, std::invalid_argument, ...
    std::cout.flush();
    if (rayint::cli::progress_line_open()) std::cerr << '\n';  // the error on a line of its own
    std::cerr << "rayint: error: " << rayint::field::one_line(e.what()) << "\n";
    return rayint::cli::kExitBadInput;
  }
  if (app.get_subcommands().empty()) {  // `rayint` alone: what it can do, on stderr
    std::cerr << app.help();
    return rayint::cli::kExitBadInput;
  }
  if (!flush_stdout()) return rayint::cli::kExitBadInput;
  return status;
}
