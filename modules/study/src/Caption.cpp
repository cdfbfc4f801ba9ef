#include "mvw/study/Caption.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

namespace mvw::study {

namespace {

// `v` to `significant` digits, %g style: "300", "2.5" (an SUV isosurface is not "iso 2").
std::string significant(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace

std::string volumeName(const Volume& v, const char* role) {
  const VolumeMetadata& md = v.metadata();
  const std::string modality = md.modality == "PT" ? "PET" : md.modality;
  // The series description, or the file's name without its extensions (a DICOM folder's name
  // where the series has no description).
  std::string what = md.seriesDescription;
  if (what.empty() && !md.sourcePath.empty()) {
    std::filesystem::path file = std::filesystem::path(md.sourcePath).filename();
    while (file.has_extension() && file.extension().string().size() <= 4) file = file.stem();
    what = file.string();
  }
  if (what.size() > 24) what = what.substr(0, 22) + "..";
  if (what.empty()) return modality.empty() ? role : modality;
  // "PET WB" rather than "PET PET WB": a description that starts with the modality says it.
  const auto startsWithModality = [&] {
    if (modality.empty() || what.size() < modality.size()) return false;
    for (std::size_t i = 0; i < modality.size(); ++i)
      if (std::toupper(static_cast<unsigned char>(what[i])) != modality[i]) return false;
    return what.size() == modality.size() ||
           !std::isalnum(static_cast<unsigned char>(what[modality.size()]));
  };
  if (modality.empty() || startsWithModality()) return what;
  return modality + " " + what;
}

std::string viewCaption(const PlannedView& v, const WindowLevel& shown) {
  const render::RenderSettings& s = v.settings;
  std::string caption = toString(v.config.mode);
  if (s.mode == render::RenderMode::Mpr) caption += " " + config::toString(v.config.view);
  if (s.mode == render::RenderMode::Mpr && s.slabMm > 0)
    caption += "  slab " + std::to_string(static_cast<int>(s.slabMm)) + " mm";
  if (s.mode == render::RenderMode::Composite)
    caption += "  " + v.presetName;
  else if (s.mode == render::RenderMode::Isosurface)
    caption += "  iso " + significant(s.iso, 4);
  else
    caption += "  W " + std::to_string(static_cast<int>(shown.window)) + " L " +
               std::to_string(static_cast<int>(shown.level));
  if (render::showsImageColors(s)) caption += "  " + toString(s.imageColors->map);
  if (s.glyphs.on &&
      (s.mode == render::RenderMode::Composite || s.mode == render::RenderMode::Isosurface))
    caption += "  glyphs " + config::toString(v.config.glyphs.method) + " " +
               (s.glyphLabels.empty() ? config::toString(v.config.glyphs.convexity)
                                      : std::string("by chosen label"));
  // Only where the image shows it (a planned view with fusion has a functional volume): MPR
  // shows its overlay, and the shell modes cannot fuse.
  if (render::showsFusion(s, true)) {
    caption += "  + colour fusion";
    if (isProjectionMode(s.mode))
      caption += takesFusionMean(s.mode) && s.overlay.projection == FusionProjection::Mean
                     ? " (functional mean)"
                     : " (functional max)";
  }
  const bool shells = isShellMode(s.mode);
  if (shells) caption += "  " + std::to_string(s.shells) + " shells";
  if ((s.mode == render::RenderMode::Mip || shells) && s.depthCue.on) {
    char cue[96];
    std::snprintf(cue, sizeof cue, "  depth cue b0 %.2f a %.2f b %.2f", s.depthCue.brightness,
                  s.depthCue.amount, s.depthCue.contrast);
    caption += cue;
  }
  return caption;
}

namespace {

// A legend's value: three significant digits.
std::string number(double v) { return significant(v, 3); }

}  // namespace

render::GlyphLegend glyphLegend(const PlannedView& v, const std::string& unit,
                                std::pair<double, double> range) {
  const render::RenderSettings& s = v.settings;
  render::GlyphLegend legend;
  if (!s.glyphs.on) return legend;
  // The apparent bump radius for an attribute u in 0..1 (shaders/common/glyphs.glsl): eq. (1)
  // blends at full size; eqs. (2)-(3) run from the minimum size to 1 (paper: from 0).
  const bool paper = s.glyphMap.placement == render::GlyphPlacement::Paper;
  const bool both = s.glyphs.convexity == GlyphConvexity::Both || !s.glyphLabels.empty();
  auto bump = [&](double u, std::string label, std::optional<double> value) {
    const double beta = both ? 2.0 * u - 1.0 : u;
    const double size =
        s.glyphs.method == GlyphMethod::Simple ? (beta == 0.0 ? 0.0 : 1.0)
        : paper
            ? std::abs(beta)
            : (beta == 0.0 ? 0.0 : s.glyphs.minSize + (1.0 - s.glyphs.minSize) * std::abs(beta));
    const bool dimple = s.glyphs.convexity == GlyphConvexity::Dimples || (both && beta < 0.0);
    legend.entries.push_back(
        {std::move(label), size, dimple ? GlyphKind::Dimples : GlyphKind::Bumps, {}, value});
  };
  if (!s.glyphLabels.empty()) {
    legend.title = "glyphs: chosen labels";
    for (const render::LabelGlyph& l : s.glyphLabels) {
      if (legend.entries.size() == 10) {
        legend.entries.push_back({"... " + std::to_string(s.glyphLabels.size() - 10) + " more",
                                  0.0,
                                  {},
                                  {},
                                  std::nullopt});
        break;
      }
      legend.entries.push_back(
          {std::to_string(l.label) + (l.name.empty() ? "" : " " + l.name) +
               (render::usesGlyphKinds(s) ? std::string("  ") + glyphKindName(l.kind) : ""),
           1.0,
           l.kind,
           {},
           double(l.label)});
    }
    return legend;
  }
  if (s.functionalClasses > 0) {
    const int k = s.functionalClasses;
    legend.title = "glyphs: label mod " + std::to_string(k);
    for (int c = 0; c < std::min(k, 8); ++c) {
      bump(double(c + 1) / k, "labels " + std::to_string(c) + " mod " + std::to_string(k),
           double(c == 0 ? k : c));     // a label of the class
      if (render::usesGlyphKinds(s)) {  // issue 40: each class its kind as well as its size
        const GlyphKind kind =
            s.glyphs.classKinds[std::min<std::size_t>(c, s.glyphs.classKinds.size() - 1)];
        legend.entries.back().kind = kind;
        legend.entries.back().label += std::string("  ") + glyphKindName(kind);
      }
    }
    return legend;
  }
  const auto [lo, hi] = s.functionalWindow.orRange(range.first, range.second);
  legend.title = "glyphs: " + (unit.empty() ? std::string("attribute") : unit);
  legend.low = lo, legend.high = hi;
  if (render::usesGlyphKinds(s)) {
    // An ordinal attribute in classes (issue 40): the window's equal ranges, each its kind,
    // the icon at the range's middle (the size the window gives there).
    const int n = int(s.glyphs.classKinds.size());
    bump(0.0, "<= " + number(lo) + "  none", std::nullopt);
    for (int c = 0; c < n; ++c) {
      const double a = lo + (hi - lo) * c / n, b = lo + (hi - lo) * (c + 1) / n;
      const double u = (c + 0.5) / n;
      const GlyphKind kind = s.glyphs.classKinds[std::size_t(c)];
      bump(u, number(a) + " - " + number(b) + (c + 1 == n ? "+" : "") + "  " + glyphKindName(kind),
           lo + u * (hi - lo));
      legend.entries.back().kind = kind;
    }
    return legend;
  }
  bump(0.0, "<= " + number(lo) + "  none", std::nullopt);
  const std::vector<double> steps =
      both ? std::vector<double>{1e-3, 0.25, 0.75, 1.0} : std::vector<double>{1e-3, 0.5, 1.0};
  for (double u : steps) bump(u, number(lo + u * (hi - lo)), lo + u * (hi - lo));
  legend.entries[1].label = "> " + number(lo);  // just above the low end
  return legend;
}

}  // namespace mvw::study
