#pragma once
// The 2D transfer function's gradient term: opacity scaled by smoothstep(low, high, |gradient|)
// (the volume's unit per mm), which keeps boundaries and hides homogeneous regions (Levoy). One
// value for the study config's view (config::ViewConfig: "gradient_opacity") and the renderer
// (render::RenderSettings), which go with the transfer function itself: the config names a
// preset, the renderer holds the function that render::transferPreset, the one conversion,
// makes of the name. Its key, range and default: the config's view table (modules/config,
// docs/config-reference.md).
namespace mvw {

struct GradientOpacity {
  double low = 0.0;
  double high = 0.0;
  // high <= 0: off, the 1D transfer function alone.
  bool on() const { return high > 0.0; }
  bool operator==(const GradientOpacity&) const = default;
};

}  // namespace mvw
