// rayint check CASE.json --candidate THEIRS.json -- another renderer's per-ray intensities
// against the exact values; writes a JSON diff (docs/candidate-format.md). Exit 0 when every
// channel of every ray is within tolerance, 1 when one is not, 2 on bad input. Mesh cases of cells
// other than tetrahedra are checked against the cells' own interpolation (check_candidate_own).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "check_image.hpp"
#include "commands.hpp"
#include "float_range.hpp"
#include "options.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/report/junit.hpp"
#include "rayint/studies/check.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/report/check_json.hpp"
#include "rayint/report/check_summary.hpp"
#include "rayint/input/case_reader.hpp"

namespace rayint::cli {

void set_check_command(CLI::App& app) {
  struct Options {
    std::string case_file;
    std::string candidate_file;
    std::string output;
    CheckOptions check;
    bool no_reference = false;
    MeshReadOptions mesh;
    ImageCheckOptions image;  // --candidate-image
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Compare another renderer's per-ray intensities with the exact values");
  cmd->add_option("case", opt->case_file, "Case file (JSON)")->required();
  auto* candidate_json = cmd->add_option("--candidate", opt->candidate_file,
                                    "The renderer's intensities (JSON, docs/candidate-format.md)");
  auto* candidate_image = cmd->add_option(
      "--candidate-image", opt->image.candidate_image,
      "The renderer's image of a mesh case's camera or of a scene (.pfm, .exr, .npy; .png only to "
      "~1/255), compared pixel by pixel with the exact image or the scene's reference image "
      "(README, \"Checking a renderer's image\")");
  candidate_json->excludes(candidate_image);
  cmd->add_flag("--flip-x", opt->image.flip_x, "Images: mirror the candidate left-right first");
  cmd->add_flag("--flip-y", opt->image.flip_y,
                "Images: mirror the candidate top-bottom first (rows stored bottom-up, e.g. OpenGL)");
  cmd->add_option("--candidate-alpha", opt->image.alpha_mode,
                  "Images: how the candidate's alpha channel (.npy (H, W, 4), .exr A) is meant: ignore "
                  "(compare RGB as is), premultiplied (RGB + (1 - A) * background) or straight "
                  "(A * RGB + (1 - A) * background), composited over the case's background")
      ->check(CLI::IsMember({"ignore", "premultiplied", "straight"}))
      ->capture_default_str();
  cmd->add_option("--worst", opt->image.worst, "Images: how many worst pixels to write as case files")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_option("--artifacts", opt->image.artifacts,
                  "Images: folder (created when missing) for error_heat_map.png and worst_pixel_<i>.json; "
                  "without it nothing but the diff is written")
      ->capture_default_str();
  cmd->add_option("--junit", opt->image.junit, "Also write the result as JUnit XML to this file");
  add_threads_option(cmd, opt->image.threads, "Images: render threads (0: all cores)");
  cmd->add_option("--candidate-variance", opt->image.candidate_variance,
                  "Monte Carlo images: per-pixel variance of the candidate's mean (or per sample, "
                  "with --samples); switches to the per-pixel z-test with Holm's correction")
      ->needs(candidate_image);
  cmd->add_option("--samples", opt->image.samples,
                  "Monte Carlo images: samples per pixel; the variance image is then per sample")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--alpha", opt->image.alpha,
                  "z-test: family-wise significance level (Holm-Bonferroni)")
      ->check(float_range(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--min-fraction", opt->image.min_fraction,
                  "z-test: pass when at least this fraction of pixel channels pass (Mitsuba 3: 0.9975)")
      ->check(float_range(0.0, 1.0))
      ->capture_default_str();
  add_tolerance_options(cmd, opt->check.rel_tol, opt->check.abs_tol,
                        "Relative tolerance: a channel passes if "
                        "|got - expected| <= max(abs-tol, rel-tol * |expected|)");
  cmd->add_flag("--no-reference", opt->no_reference,
                "Skip the 50-digit reference (reported for context only; costs time on big cases)");
  add_output_option(cmd, opt->output, "Write the diff to this file instead of stdout");
  add_strict_mesh_flag(cmd, opt->mesh.strict);
  add_cells_option(cmd, opt->mesh.split_cells);
  add_quiet_flag(cmd, opt->image.quiet);  // the verdict line on stderr; the diff and exit status stay
  cmd->callback([opt, candidate_json, candidate_image] {
    if (candidate_image->count() > 0) {
      ImageCheckOptions io = opt->image;
      io.case_file = opt->case_file;
      io.mesh = opt->mesh;
      io.rel_tol = opt->check.rel_tol;
      io.abs_tol = opt->check.abs_tol;
      io.output = opt->output;
      run_image_check(io);
      return;
    }
    if (candidate_json->count() == 0)
      throw CLI::RequiredError("--candidate or --candidate-image");
    // A mesh case of cells other than tetrahedra comes back in `own` (no segments): its expected
    // values are the cells' own interpolation (studies/check.hpp check_candidate_own).
    std::optional<MeshCase> own;
    const Case c = read_case_file(opt->case_file, opt->mesh, nullptr, &own);
    const Candidate candidate =
        read_case_candidate(opt->candidate_file, true, opt->candidate_file, c, own ? &*own : nullptr);
    CheckOptions co = opt->check;
    co.with_reference = !opt->no_reference;
    if (own && !opt->image.quiet)
      std::fprintf(stderr, "rayint check: mode own: the expected intensities integrate the cells in their own "
                   "(isoparametric) interpolation (--cells split: VTK's tetrahedralisation)\n");
    const CheckResult result = own ? check_candidate_own(*own, candidate, co) : check_candidate(c, candidate, co);
    emit(check_report_json(result).dump(2), opt->output);
    if (!opt->image.junit.empty())
      write_file_atomically(opt->image.junit, junit_xml({check_junit(result)}));
    std::cout.flush();
    if (!opt->image.quiet) std::cerr << check_summary_line(result) << std::endl;
    // The callback cannot return an exit code and main() maps exceptions to 2 (bad input), so a
    // failed check ends here with 1, after its diff is written and flushed.
    if (!result.pass) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
