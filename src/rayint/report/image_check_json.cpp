#include "rayint/report/image_check_json.hpp"

#include <cmath>

#include "rayint/report/json_number.hpp"
#include "rayint/report/text_format.hpp"

namespace rayint {
namespace {

const char* kChannelNames[3] = {"r", "g", "b"};

}  // namespace

const char* pixel_convention_text() {
  return "pixel (x, y) is the ray through the pixel centre ((x + 0.5)/width, (y + 0.5)/height); "
         "row y = 0 is the top of the image and y runs down; x = 0 is the left (before --flip-x/--flip-y "
         "are applied to the candidate)";
}

nlohmann::ordered_json image_check_json(const ImageCheckContext& ctx, const ImageComparison& c) {
  nlohmann::ordered_json j;
  const ZTestResult* z = ctx.z_test;
  j["pass"] = z ? z->pass : c.pass;
  j["decided_by"] = z ? "z_test" : "tolerance";
  j["case"] = ctx.case_name;
  j[ctx.scene_reference ? "scene_file" : "case_file"] = ctx.case_source;
  if (const ImageCheckContext::SceneReference* r = ctx.scene_reference) {
    nlohmann::ordered_json ref;
    ref["what"] = "the scene's reference image: each named term by its effect's independent reference, "
                  "summed as rayint render sums the terms";
    ref["image"] = r->image.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r->image);
    ref["max_error_estimate"] = number_or_null<nlohmann::ordered_json>(r->max_error);
    ref["unconverged_pixels"] = r->unconverged;
    ref["evaluations"] = r->evaluations;
    ref["seconds"] = r->seconds;
    if (r->variance_added)
      ref["z_test"] = "the reference's error estimate is taken as two standard errors: (error / 2)^2 is "
                      "added to the candidate's variance";
    j["reference"] = ref;
  }
  j["candidate_image"] = ctx.candidate_source;
  j["pixel_convention"] = pixel_convention_text();
  j["flip_x"] = ctx.flip_x;
  j["flip_y"] = ctx.flip_y;
  if (!ctx.alpha_mode.empty())
    j["candidate_alpha"] = ctx.alpha_mode + ": composited over the case's background before the comparison";
  j["rule"] = "|got - expected| <= max(abs_tol, rel_tol * |expected|) for every channel of every pixel";
  j["rel_tol"] = ctx.rel_tol;
  j["abs_tol"] = ctx.abs_tol;
  j["width"] = c.width;
  j["height"] = c.height;
  j["pixels"] = c.pixels;
  j["failed_pixels"] = c.failed_pixels;
  j["failed_channels"] = c.failed_channels;
  j["non_finite_channels"] = c.non_finite;
  j["fraction_within_tolerance"] = c.fraction_within;
  j["abs_error"] = {{"max", number_or_null<nlohmann::ordered_json>(c.max_abs)}, {"mean", number_or_null<nlohmann::ordered_json>(c.mean_abs)}, {"p99", number_or_null<nlohmann::ordered_json>(c.p99_abs)}};
  j["rel_error"] = {{"max", number_or_null<nlohmann::ordered_json>(c.max_rel)}, {"mean", number_or_null<nlohmann::ordered_json>(c.mean_rel)}, {"p99", number_or_null<nlohmann::ordered_json>(c.p99_rel)}};
  if (std::isinf(c.psnr) && c.psnr > 0) j["psnr_db"] = "inf";
  else j["psnr_db"] = number_or_null<nlohmann::ordered_json>(c.psnr);
  j["heat_map"] = ctx.heat_map.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(ctx.heat_map);
  nlohmann::ordered_json worst = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < c.worst.size(); ++i) {
    const PixelDiff& w = c.worst[i];
    nlohmann::ordered_json p;
    p["x"] = w.x;
    p["y"] = w.y;
    p["channel"] = kChannelNames[w.channel];
    p["expected"] = number_or_null<nlohmann::ordered_json>(w.expected);
    p["got"] = number_or_null<nlohmann::ordered_json>(w.got);
    p["abs_error"] = number_or_null<nlohmann::ordered_json>(w.abs_error);
    p["rel_error"] = number_or_null<nlohmann::ordered_json>(w.rel_error);
    p["allowed"] = number_or_null<nlohmann::ordered_json>(w.allowed);
    p["pass"] = w.pass;
    if (i < ctx.worst_cases.size() && !ctx.worst_cases[i].empty())
      p[ctx.scene_reference ? "scene_file" : "case_file"] = ctx.worst_cases[i];
    worst.push_back(p);
  }
  j["worst_pixels"] = worst;
  if (z) {
    nlohmann::ordered_json t;
    t["pass"] = z->pass;
    t["variance_image"] = ctx.variance_source;
    t["variance_is"] = ctx.samples > 0 ? "per sample, divided by samples" : "of the pixel mean";
    if (ctx.samples > 0) t["samples"] = ctx.samples;
    t["test"] = "per pixel and channel z = |mean - exact| / sqrt(variance of the mean), two-sided p = erfc(|z|/sqrt(2))";
    t["correction"] = "Holm-Bonferroni, family-wise error rate alpha";
    t["alpha"] = ctx.alpha;
    t["min_fraction"] = ctx.min_fraction;
    t["tests"] = z->tests;
    t["rejected"] = z->rejected;
    t["fraction_passing"] = z->fraction_passing;
    t["min_p"] = z->min_p;
    t["smallest_threshold"] = z->holm_threshold;
    t["worst"] = {{"x", z->worst_x}, {"y", z->worst_y}, {"channel", kChannelNames[z->worst_channel]},
                  {"abs_z", number_or_null<nlohmann::ordered_json>(z->worst_z)}};
    j["z_test"] = t;
    j["tolerance_note"] = "in z-test mode the tolerance figures above are for information; the z-test decides";
  }
  if (!ctx.note.empty()) j["note"] = ctx.note;
  if (!ctx.mode.empty()) {
    j["mode"] = ctx.mode;
    if (ctx.mode == "own") j["failed_pixels"] = ctx.failed_pixels;
  }
  return j;
}

std::string image_check_summary_line(const ImageCheckContext& ctx, const ImageComparison& c) {
  std::string s = "check " + ctx.case_name + " (image " + std::to_string(c.width) + " x " +
                  std::to_string(c.height) + "): ";
  if (ctx.z_test) {
    const ZTestResult& z = *ctx.z_test;
    return s + (z.pass ? "PASS" : "FAIL") + " (z-test, Holm at alpha " + g3(ctx.alpha) + "), " +
           std::to_string(z.rejected) + " of " + std::to_string(z.tests) +
           " pixel channels rejected, fraction passing " + g3(z.fraction_passing) + " (limit " +
           g3(ctx.min_fraction) + "); max abs " + g3(c.max_abs) + ", PSNR " +
           (std::isinf(c.psnr) && c.psnr > 0 ? std::string("inf") : g3(c.psnr)) + " dB";
  }
  s += std::string(c.pass ? "PASS" : "FAIL") + ", " +
                  std::to_string(c.failed_pixels) + " of " + std::to_string(c.pixels) +
                  " pixels outside tolerance; max abs " + g3(c.max_abs) + ", max rel " + g3(c.max_rel) +
                  ", PSNR " + (std::isinf(c.psnr) && c.psnr > 0 ? std::string("inf") : g3(c.psnr)) + " dB";
  if (!c.pass && !c.worst.empty())
    s += "; worst pixel (" + std::to_string(c.worst[0].x) + ", " + std::to_string(c.worst[0].y) + ")";
  return s;
}

}  // namespace rayint
