#pragma once
// The windows that map a volume's values to the display, one value each for the study config's
// view (config::ViewConfig) and the renderer (render::RenderSettings), so planning a view moves
// them whole. Each has one unset form, the one fallback every view uses. Their keys, ranges and
// defaults: the config's view table (modules/config, docs/config-reference.md).
//
// Two types, not one: the anatomy's window is given and shown as width and centre ("window",
// "level", the uWindowLevel uniform, "W 400 L 40" captions), the functional one as its ends
// ("functional_window": [low, high], the viewer's low / high sliders). Turning one form into the
// other rounds, so each keeps the form it is given in.
namespace mvw {

// The grey-level window of a projection, an MPR or a cut face: width and centre in the
// volume's unit. A width that is not positive is unset: the full value range.
struct WindowLevel {
  double window = 0.0;
  double level = 0.0;
  bool set() const { return window > 0.0; }
  bool operator==(const WindowLevel&) const = default;
};

// (window, level) when set; otherwise the range [lo, hi].
WindowLevel windowOrFullRange(const WindowLevel& window, double lo, double hi);

// The functional values mapped to 0 .. 1 (colour overlay and fusion, glyph size): its ends in
// the volume's unit. low >= high is unset: the volume's value range (or its kind's default).
struct ValueWindow {
  double low = 0.0;
  double high = 0.0;
  bool set() const { return high > low; }
  // This window where set; otherwise [lo, hi] (the volume's value range): the one fallback of
  // the overlay, the glyphs, their legend and the colour bar.
  ValueWindow orRange(double lo, double hi) const { return set() ? *this : ValueWindow{lo, hi}; }
  bool operator==(const ValueWindow&) const = default;
};

}  // namespace mvw
