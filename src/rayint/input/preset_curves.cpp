#include "rayint/input/preset_curves.hpp"

#include "rayint/input/json_source.hpp"

namespace rayint {

PresetCurvesImport import_preset_curves(const PresetImportRequest& r) {
  PresetCurvesImport out;
  out.import = import_paraview_preset(r);
  const ParaViewPreset& p = out.import.preset;
  PresetCurves& c = out.curves;
  c.color = p.color;
  c.options = r.options;
  // The opacity import_paraview_preset_text used, rebuilt the way it builds it.
  if (r.constant_opacity) {
    c.opacity_source = PresetOpacitySource::constant;
    c.opacity.nodes.push_back({p.color.nodes.front().x, *r.constant_opacity, 0.5, 0.0});
  } else if (out.import.default_opacity) {
    c.opacity_source = PresetOpacitySource::default_ramp;
    const double x0 = p.color.nodes.front().x, x1 = p.color.nodes.back().x;
    if (x1 > x0) {
      c.opacity.nodes.push_back({x0, 0.0, 0.5, 0.0});
      c.opacity.nodes.push_back({x1, 1.0, 0.5, 0.0});
    } else {
      c.opacity.nodes.push_back({x0, 1.0, 0.5, 0.0});
    }
  } else {
    c.opacity_source = PresetOpacitySource::points;
    c.opacity = *p.opacity;
  }
  if (r.range) {
    // The colour range before rescaling: the preset as the file has it.
    const ParaViewPreset original = parse_paraview_preset(
        json_source::read_text_file(r.file), r.file, PresetSelection{r.name, r.index, r.request_source, r.index_field});
    c.rescale = std::array<double, 4>{original.color.nodes.front().x, original.color.nodes.back().x, (*r.range)[0],
                                      (*r.range)[1]};
  }
  return out;
}

}  // namespace rayint
