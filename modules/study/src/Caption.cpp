#include "mvw/study/Caption.h"

#include <cstdio>

namespace mvw::study {

std::string viewCaption(const PlannedView& v, const WindowLevel& shown) {
  const render::RenderSettings& s = v.settings;
  std::string caption = toString(v.config.mode);
  if (s.mode == render::RenderMode::Mpr) caption += " " + config::toString(v.config.view);
  if (s.mode == render::RenderMode::Mpr && s.slabMm > 0)
    caption += "  slab " + std::to_string(static_cast<int>(s.slabMm)) + " mm";
  if (s.mode == render::RenderMode::Composite)
    caption += "  " + v.presetName;
  else if (s.mode == render::RenderMode::Isosurface)
    caption += "  iso " + std::to_string(static_cast<int>(s.isoValue));
  else
    caption += "  W " + std::to_string(static_cast<int>(shown.window)) + " L " +
               std::to_string(static_cast<int>(shown.level));
  if (render::showsImageColors(s)) caption += "  " + toString(s.imageColors->map);
  if (s.glyphs &&
      (s.mode == render::RenderMode::Composite || s.mode == render::RenderMode::Isosurface))
    caption += "  glyphs " + config::toString(v.config.glyphMethod) + " " +
               config::toString(v.config.glyphConvexity);
  if (s.fusion) caption += "  + colour fusion";
  const bool shells = isShellMode(s.mode);
  if (shells) caption += "  " + std::to_string(s.shellCount) + " shells";
  if ((s.mode == render::RenderMode::Mip || shells) && s.depthCue) {
    char cue[96];
    std::snprintf(cue, sizeof cue, "  depth cue b0 %.2f a %.2f b %.2f", s.cueBrightness,
                  s.cueAmount, s.cueContrast);
    caption += cue;
  }
  return caption;
}

}  // namespace mvw::study
