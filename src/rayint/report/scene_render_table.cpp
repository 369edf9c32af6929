#include "rayint/report/scene_render_table.hpp"

#include <cstdio>

#include "rayint/report/text_format.hpp"

namespace rayint {

std::string scene_render_table(const SceneRenderResult& r) {
  std::string s;
  appendf(s, "%-18s %-26s %10s %12s %12s %12s %12s\n", "effect", "method", "seconds", "samples",
          "shadow_rays", "max_abs_err", "rel_to_peak");
  for (const EffectReport& e : r.effects) {
    appendf(s, "%-18s %-26s %10.3f %12lld %12lld %12s %12s\n", e.effect.c_str(), e.method.c_str(),
            e.work.seconds + e.work.setup_seconds, e.work.samples, e.work.shadow_rays,
            e.has_error ? std::to_string(e.error.max_abs).c_str() : "-",
            e.has_error ? std::to_string(e.error.max_rel_to_peak).c_str() : "-");
  }
  appendf(s, "render %.3f s wall on %u threads, setup %.3f s, errors %.3f s\n", r.render_seconds,
          r.threads, r.setup_seconds, r.error_seconds);
  return s;
}

}  // namespace rayint
