#pragma once
// A view's crop box in patient terms, the same for any storage order: one value for the study
// config's view (config::ViewConfig: "crop_min", "crop_max", "crop_mm") and the renderer
// (render::RenderSettings; render::PatientCrop turns it into texture and world boxes). Its keys,
// ranges and defaults: the config's crop table (modules/config, docs/config-reference.md).
// What the cut face shows (CutFace) is not part of it: its default differs on purpose, anatomy
// in the config (what a reader gets, under the window the plan gives) and plain in the renderer
// (a look that needs no window, which settings made by hand keep).
#include <optional>

#include <glm/vec3.hpp>

namespace mvw {

struct Crop {
  // Fractions of the volume's world-aligned box along L, P, S (0 = most right / anterior /
  // inferior, 1 = most left / posterior / superior), whatever the storage order.
  glm::dvec3 min{0.0};
  glm::dvec3 max{1.0};
  // Or the box in LPS millimetres: when both are set they win over the fractions.
  std::optional<glm::dvec3> minMm, maxMm;
  bool operator==(const Crop&) const = default;
};

}  // namespace mvw
