#include "rayint/report/grad_json.hpp"

#include <cmath>
#include <string>

#include "rayint/report/json_number.hpp"

namespace rayint {
namespace {

using ojson = nlohmann::ordered_json;
constexpr const char* kChannelNames[kChannels] = {"r", "g", "b"};

ojson nodes(const std::array<std::vector<NodeDerivative>, kChannels>& per_channel) {
  ojson j = ojson::object();
  for (int c = 0; c < kChannels; ++c) {
    ojson list = ojson::array();
    for (const NodeDerivative& d : per_channel[c])
      list.push_back(ojson::array({number_or_null<ojson>(d.position), number_or_null<ojson>(d.value)}));
    j[kChannelNames[c]] = list;
  }
  return j;
}

// dI_c / d the preset's RGBPoints (x, r, g, b) and Points (x, opacity), or null with the reason.
ojson preset_json(const PresetPointGradient& p) {
  ojson out = ojson::object();
  if (p.color_ok) {
    ojson j = ojson::object();
    for (int c = 0; c < kChannels; ++c) {
      ojson list = ojson::array();
      for (const auto& e : p.rgb_points[c])
        list.push_back(ojson::array({number_or_null<ojson>(e[0]), number_or_null<ojson>(e[1]), number_or_null<ojson>(e[2]), number_or_null<ojson>(e[3])}));
      j[kChannelNames[c]] = list;
    }
    out["RGBPoints"] = j;
  } else {
    out["RGBPoints"] = nullptr;
    out["RGBPoints_unavailable"] = p.color_unavailable;
  }
  if (p.opacity_ok) {
    ojson j = ojson::object();
    for (int c = 0; c < kChannels; ++c) {
      ojson list = ojson::array();
      for (const auto& e : p.points[c]) list.push_back(ojson::array({number_or_null<ojson>(e[0]), number_or_null<ojson>(e[1])}));
      j[kChannelNames[c]] = list;
    }
    out["Points"] = j;
  } else {
    out["Points"] = nullptr;
    out["Points_unavailable"] = p.opacity_unavailable;
  }
  return out;
}

}  // namespace

ojson gradient_json(const RayGradient& g) {
  ojson length = ojson::array(), scalar = ojson::array();
  for (std::size_t j = 0; j < g.length.size(); ++j) {
    length.push_back(rgb_json<ojson>(g.length[j]));
    scalar.push_back(ojson::array({rgb_json<ojson>(g.scalar_far[j]), rgb_json<ojson>(g.scalar_exit[j])}));
  }
  ojson out = {{"background", rgb_json<ojson>(g.background)},
                {"length", length},
                {"scalar", scalar},
                {"density", nodes(g.density)},
                {"color", nodes(g.color)}};
  // Entries whose derivative does not exist are null; say why.
  if (!g.undefined.empty()) out["undefined"] = g.undefined;
  return out;
}

ojson grad_report_json(const std::vector<GradCaseResult>& cases) {
  ojson out_cases = ojson::array();
  for (const GradCaseResult& c : cases) {
    ojson rays = ojson::array();
    for (std::size_t i = 0; i < c.rays.size(); ++i) {
      const GradRayResult& r = c.rays[i];
      ojson ray = {{"index", i}};
      if (r.reference) {
        ray["reference"] = {{"intensity", rgb_json<ojson>(r.reference->gradient.intensity)},
                            {"gradient", gradient_json(r.reference->gradient)},
                            {"noise", rgb_json<ojson>(r.reference->noise)}};
        if (r.reference_preset) ray["reference"]["preset_gradient"] = preset_json(*r.reference_preset);
      } else {
        ray["reference"] = nullptr;
      }
      ojson methods = ojson::object();
      for (const GradMethodResult& m : r.methods) {
        if (!m.ok) {
          methods[m.label] = {{"intensity", nullptr}, {"gradient", nullptr}, {"error", m.error}};
          continue;
        }
        methods[m.label] = {{"intensity", rgb_json<ojson>(m.gradient.intensity)},
                            {"gradient", gradient_json(m.gradient)},
                            {"errors",
                             {{"gradient_max_rel_vs_reference", rgb_json<ojson>(m.error_vs_reference)},
                              {"gradient_max_rel_vs_exact", rgb_json<ojson>(m.error_vs_exact)},
                              {"intensity_rel_vs_reference", rgb_json<ojson>(m.intensity_error)}}}};
        if (m.preset) methods[m.label]["preset_gradient"] = preset_json(*m.preset);
      }
      ray["methods"] = methods;
      rays.push_back(ray);
    }
    ojson entry = {{"case", c.name}, {"file", c.source}};
    // A transfer function imported from a ParaView preset: the node blocks are with respect to
    // the imported nodes, and say so.
    if (!c.transfer_origin.empty())
      entry["transfer_function_nodes"] = {
          {"imported_from", c.transfer_origin},
          {"meaning", "density and color node k are node k of the imported piecewise-linear functions "
                      "(as `rayint tf import` lists them); preset_gradient (per method) is with respect to "
                      "the preset's own points: RGBPoints[k] -> [dI/dx, dI/dr, dI/dg, dI/db], Points[k] -> "
                      "[dI/dx, dI/dopacity] per channel of I, x in the preset file's scalars (before any "
                      "range); null with the reason where the import is not differentiable in them"}};
    entry["rays"] = rays;
    out_cases.push_back(entry);
  }
  return {{"tool", "rayint"},
          {"report", "grad"},
          {"errors",
           "gradient_max_rel_*: max over the channel's entries of |got - want| / (largest |want| "
           "entry of that channel); null when not computed or not finite"},
          {"cases", out_cases}};
}

ojson gradcheck_report_json(const GradCheckResult& r) {
  const auto entry = [](const std::optional<GradCheckEntry>& e) -> ojson {
    if (!e) return nullptr;
    return {{"ray", e->ray},
            {"block", e->block},
            {"index", e->index},
            {"parameter", e->parameter},
            {"channel", kChannelNames[e->channel]},
            {"got", number_or_null<ojson>(e->got)},
            {"exact", number_or_null<ojson>(e->exact)},
            {"allowed", number_or_null<ojson>(e->allowed)},
            {"excess", number_or_null<ojson>(e->excess)}};
  };
  return {{"tool", "rayint"},
          {"report", "gradcheck"},
          {"pass", r.passed()},
          {"case", r.case_name},
          {"renderer", r.renderer},
          {"against", r.against == GradCheckAgainst::reference ? "reference" : "exact"},
          {"rule", r.against == GradCheckAgainst::reference
                       ? "pass if |got - reference| <= max(abs_tol, rel_tol * largest |reference| entry of the "
                         "ray's channel) for every entry; an entry's \"exact\" holds the reference's value"
                       : "pass if |got - exact| <= max(abs_tol, rel_tol * largest |exact| entry of the ray's "
                         "channel) for every entry"},
          {"exact_vs_reference", r.against == GradCheckAgainst::reference ? rgb_json<ojson>(r.exact_vs_reference)
                                                                        : ojson(nullptr)},
          {"rel_tol", r.rel_tol},
          {"abs_tol", r.abs_tol},
          {"entries", r.entries},
          {"failed", r.failed},
          {"null_in_candidate", r.null_in_candidate},
          {"first_null", entry(r.first_null)},
          {"undefined", r.undefined},
          {"undefined_reason", r.undefined_reason.empty() ? ojson(nullptr) : ojson(r.undefined_reason)},
          {"worst", entry(r.worst)}};
}

}  // namespace rayint
