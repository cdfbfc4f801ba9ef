#pragma once
// MIP depth cueing (Heidrich et al. 1995, eq. 3 and section 2.3): one value for the study
// config's view ("depth_cue": {...}, config::ViewConfig) and the renderer
// (render::RenderSettings), so planning a view moves it whole. Off, or amount 0, contrast 1
// and brightness 0: a plain MIP. Its keys, ranges and defaults: the config's depth cue table
// (modules/config, docs/config-reference.md).
namespace mvw {

struct DepthCue {
  bool on = false;          // the view's "depth_cue" object is present
  double brightness = 0.0;  // beta0
  double amount = 0.0;      // a
  double contrast = 1.0;    // b
  bool operator==(const DepthCue&) const = default;
};

}  // namespace mvw
