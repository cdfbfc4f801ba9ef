#include "ViewerPanel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "mvw/core/Format.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/TransferFunction.h"
#include "mvw/study/ModalityDefaults.h"
#include "mvw/viewer/PanelText.h"
#include "mvw/viewer/ViewControls.h"

namespace mvw::app {

// The window draws the window-free viewer (mvw::viewer) and acts through it throughout.
using namespace mvw::viewer;

namespace {
const char* kModeLabels[] = {"composite", "isosurface", "mip (depth cue: D)", "minip", "average"};

// A colour map chooser: every map by its config name.
void colormapCombo(ViewerState& state, const char* label, ColorTarget target) {
  const ColorMap current = state.colormap(target);
  if (ImGui::BeginCombo(label, toString(current).c_str())) {
    for (const std::string& n : colorMapNames()) {
      const ColorMap map = *parseColorMap(n);
      if (ImGui::Selectable(n.c_str(), map == current)) state.setColormap(target, map);
    }
    ImGui::EndCombo();
  }
}

// The label picker (issue 15 items 4 and 8): which labels of a label map carry glyphs and of
// which kind, as the config's glyphs.labels (Ctrl+S saves them). The filter narrows the
// atlas's names; without a label table the labels are numbered up to the volume's maximum.
void glyphLabelPicker(ViewerState& state) {
  const std::vector<render::LabelGlyph> chosen = state.view3d().glyphLabels;
  const std::string header = glyphPickerHeader(chosen.size());
  ImGui::SetNextItemOpen(!chosen.empty(), ImGuiCond_Once);  // open where the study chose some
  if (!ImGui::CollapsingHeader(header.c_str())) return;
  static ImGuiTextFilter filter;
  filter.Draw("filter");
  const auto labels = glyphPickerLabels(state.labelNames(), state.scene().functionalRange.second);
  // config::LabelGlyphKind's order: bumps, dimples, none, then the other kinds (issue 40).
  const char* kinds[] = {"bumps", "dimples", "none", "rings", "ridges", "cones", "crosses"};
  ImGui::BeginChild("glyph-label-list", ImVec2(0, 180), true);
  for (const auto& [n, name] : labels) {
    const std::string text = std::to_string(n) + (name.empty() ? "" : " " + name);
    if (!filter.PassFilter(text.c_str())) continue;
    const auto it = std::find_if(chosen.begin(), chosen.end(),
                                 [n = n](const render::LabelGlyph& g) { return g.label == n; });
    int kind = it == chosen.end() ? 2 : static_cast<int>(config::labelGlyphKind(it->kind));
    ImGui::PushID(n);
    ImGui::SetNextItemWidth(90);
    if (ImGui::Combo("##kind", &kind, kinds, IM_ARRAYSIZE(kinds)))
      state.setGlyphLabel(n, static_cast<config::LabelGlyphKind>(kind));
    ImGui::SameLine();
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopID();
  }
  ImGui::EndChild();
  if (!chosen.empty() && ImGui::Button("glyphs on every label again"))
    for (const render::LabelGlyph& g : chosen)
      state.setGlyphLabel(g.label, config::LabelGlyphKind::None);
}
// Text readable on any image: a dark box under it.
void boxedText(ImDrawList* draw, ImVec2 at, ImU32 colour, const std::string& text) {
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  draw->AddRectFilled(ImVec2(at.x - 2, at.y - 1), ImVec2(at.x + size.x + 2, at.y + size.y + 1),
                      IM_COL32(0, 0, 0, 190), 2.0f);
  draw->AddText(at, colour, text.c_str());
}

// One volume's lines of a sphere's statistics.
void statsLine(const std::string& volume, const std::optional<study::RoiStats>& s,
               const std::string& problem) {
  if (!s) {
    ImGui::TextWrapped("  %s: %s", volume.c_str(), problem.c_str());
    return;
  }
  for (const std::string& line : roiStatsLines(volume, *s)) ImGui::TextUnformatted(line.c_str());
}

const ImU32 kRoiColour = IM_COL32(80, 255, 120, 255);
// Labels and centre marks lighter than the circle: a test can tell the circles apart.
const ImU32 kRoiTextColour = IM_COL32(190, 255, 200, 255);
const ImU32 kRulerColour = IM_COL32(255, 220, 60, 255);

}  // namespace

void ViewerPanel::drawMeasurements(int pane, ImVec2 pos, ImVec2 size) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  auto at = [&](glm::dvec2 f) {
    return ImVec2(pos.x + static_cast<float>(f.x) * size.x,
                  pos.y + static_cast<float>(f.y) * size.y);
  };
  draw->PushClipRect(pos, ImVec2(pos.x + size.x, pos.y + size.y), true);
  const ViewerMeasurements& measurements = state_.measurements();
  std::vector<config::SphereMeasurement> spheres = measurements.all().spheres;
  const std::size_t saved = spheres.size();
  if (auto p = measurements.pendingSphere()) spheres.push_back(*p);
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const auto c = measurements.paneCircle(pane, spheres[i]);
    if (!c) continue;
    const ImVec2 centre = at(c->centre);
    const float rx = static_cast<float>(c->radius.x) * size.x;
    draw->AddCircle(centre, std::max(1.0f, rx), kRoiColour, 64, 2.0f);
    draw->AddLine(ImVec2(centre.x - 3, centre.y), ImVec2(centre.x + 3, centre.y), kRoiTextColour);
    draw->AddLine(ImVec2(centre.x, centre.y - 3), ImVec2(centre.x, centre.y + 3), kRoiTextColour);
    boxedText(draw, ImVec2(centre.x + rx * 0.72f + 4, centre.y - rx * 0.72f - 14), kRoiTextColour,
              sphereLabel(i, i < saved, spheres[i].radiusMm));
  }
  std::vector<config::RulerMeasurement> rulers = measurements.all().rulers;
  if (auto p = measurements.pendingRuler()) rulers.push_back(*p);
  for (const config::RulerMeasurement& r : rulers) {
    const PaneSegment seg = measurements.paneSegment(pane, r);
    if (!seg.inPlane) continue;  // a ruler shows on the slice it was drawn on
    const ImVec2 a = at(seg.from), b = at(seg.to);
    draw->AddLine(a, b, IM_COL32(0, 0, 0, 200), 4.0f);
    draw->AddLine(a, b, kRulerColour, 2.0f);
    for (const ImVec2& e : {a, b}) draw->AddCircleFilled(e, 3.0f, kRulerColour);
    boxedText(draw, ImVec2((a.x + b.x) * 0.5f + 6, (a.y + b.y) * 0.5f - 16), kRulerColour,
              fixedNumber(ViewerMeasurements::rulerLengthMm(r), 1) + " mm");
  }
  draw->PopClipRect();
}

void ViewerPanel::drawPane(int pane, ImVec2 pos, ImVec2 size) {
  const render::DisplayTexture& texture = textures_[static_cast<std::size_t>(pane)];
  state_.setPaneSize(pane, glm::ivec2(std::max(8, static_cast<int>(size.x)),
                                      std::max(8, static_cast<int>(size.y))));
  state_.setPaneOrigin(pane, glm::ivec2(static_cast<int>(pos.x), static_cast<int>(pos.y)));
  ImGui::SetCursorScreenPos(pos);
  ImGui::PushID(pane);
  ImGui::InvisibleButton("pane", size,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  if (!texture.empty())
    draw->AddImage(reinterpret_cast<ImTextureID>(texture.handle()), pos,
                   ImVec2(pos.x + size.x, pos.y + size.y));
  ImGuiIO& io = ImGui::GetIO();
  const ImVec2 mouse = io.MousePos;
  const double fx = (mouse.x - pos.x) / size.x, fy = (mouse.y - pos.y) / size.y;
  ViewerMeasurements& measurements = state_.measurements();
  if (ImGui::IsItemHovered()) {
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) state_.toggleMaximised(pane);
    if (io.MouseWheel != 0.0f) state_.wheel(pane, io.MouseWheel, io.KeyCtrl);
    // The tool, or Shift (sphere) / Alt (ruler) whatever the tool: a measurement starts.
    const MprTool tool = io.KeyShift ? MprTool::Sphere
                         : io.KeyAlt ? MprTool::Ruler
                                     : measurements.tool();
    if (pane != k3d && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.KeyCtrl) {
      if (tool == MprTool::Crosshair)
        state_.click(pane, fx, fy);
      else
        measurements.beginGesture(pane, tool, fx, fy);
    }
    // Only a moving mouse sets the cursor: a still one leaves it where a script's hover put it,
    // and a pointer that merely rests over a pane when the window opens shows no readout there
    // (it would differ from the pane's headless render).
    if (pane != k3d && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0))
      state_.setCursor(pane, fx, fy);
  }
  for (int b = 0; b < 3; ++b)
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(b, 0.0f)) {
      const ImVec2 d = io.MouseDelta;
      if (d.x != 0 || d.y != 0) {
        if (pane != k3d && b == 0 && measurements.measuring())
          measurements.moveGesture(fx, fy);
        else if (pane != k3d && b == 0 && !io.KeyCtrl)
          state_.click(pane, fx, fy);
        else
          state_.drag(pane, d.x / size.x, d.y / size.y, static_cast<MouseButton>(b), io.KeyCtrl);
        dragging_ = true;
      }
    }
  if (measurements.measuring() && ImGui::IsMouseReleased(ImGuiMouseButton_Left))
    measurements.endGesture();
  if (pane != k3d && !texture.empty()) {
    drawMeasurements(pane, pos, size);
    // The values under the cursor, both volumes with their units, by the cursor on its pane.
    if (const auto c = state_.cursor(); c && c->first == pane) {
      const glm::dvec2 f = measurements.toPane(pane, c->second);
      const ImVec2 at(pos.x + float(f.x) * size.x, pos.y + float(f.y) * size.y);
      const std::string text = state_.readout(c->second);
      const float w = ImGui::CalcTextSize(text.c_str()).x;
      draw->PushClipRect(pos, ImVec2(pos.x + size.x, pos.y + size.y), true);
      draw->AddCircle(at, 3.0f, IM_COL32(255, 255, 255, 220));
      boxedText(draw, ImVec2(std::min(at.x + 10, pos.x + size.x - w - 6), at.y + 10),
                IM_COL32(255, 255, 255, 255), text);
      draw->PopClipRect();
    }
  }
  if (pane != k3d && !texture.empty()) {  // the linked crosshair
    const glm::dvec2 c = measurements.toPane(pane, state_.crosshair());
    const float cx = pos.x + float(c.x) * size.x, cy = pos.y + float(c.y) * size.y;
    draw->AddLine(ImVec2(cx, pos.y), ImVec2(cx, pos.y + size.y), IM_COL32(80, 200, 255, 160));
    draw->AddLine(ImVec2(pos.x, cy), ImVec2(pos.x + size.x, cy), IM_COL32(80, 200, 255, 160));
  }
  // A pane that shows nothing says why, in the middle (one clause a line).
  if (const std::string message = state_.emptyPaneMessage(pane); !message.empty()) {
    // Word-wrapped to the pane, a new line after each "; ".
    const std::string why = wrapPaneMessage(message, size.x - 16.0f, [](const std::string& line) {
      return ImGui::CalcTextSize(line.c_str()).x;
    });
    const ImVec2 text = ImGui::CalcTextSize(why.c_str());
    draw->PushClipRect(pos, ImVec2(pos.x + size.x, pos.y + size.y), true);
    boxedText(
        draw,
        ImVec2(pos.x + std::max(4.0f, (size.x - text.x) * 0.5f), pos.y + (size.y - text.y) * 0.5f),
        IM_COL32(255, 210, 80, 255), why);
    draw->PopClipRect();
  }
  ImGui::PopID();
}

void ViewerPanel::drawControls() {
  // The study's name wraps (a long one was cut at the panel's edge), and every control leaves
  // room on its right for the longest label, at any font scale (issue 36 item 8: "overlay
  // colou", "step mm (0 au" at the default width).
  ImGui::TextWrapped("%s", state_.study().name.empty() ? "mvw view" : state_.study().name.c_str());
  if (openPacs_ && ImGui::Button("Open from the PACS...")) openPacs_();
  ImGui::Separator();
  float label = 0.0f;
  for (const char* text :
       {"step mm (0 auto)", "glyph spacing mm", "overlay colours", "PET/MIP colours",
        "overlay opacity", "smallest bump", "glyph method", "MPR colours"})
    label = std::max(label, ImGui::CalcTextSize(text).x);
  ImGui::PushItemWidth(-(label + ImGui::GetStyle().ItemInnerSpacing.x + 2.0f));
  drawViewControls();
  drawDepthCue();
  if (state_.functional()) drawFunctionalControls();
  drawCrosshair();
  drawMeasurementControls();
  drawHelp();
  ImGui::PopItemWidth();
}

// The layout, the 3D pane's mode, preset and sampling, the MPR window and colours, the orbit.
void ViewerPanel::drawViewControls() {
  render::RenderSettings& v = state_.view3d();
  // The layout (key L): standard, or PET/CT (anatomical, functional, fused MPR of one plane
  // and the functional volume's rotating MIP).
  const char* layouts[] = {"standard", "PET/CT axial", "PET/CT coronal", "PET/CT sagittal"};
  int layout = static_cast<int>(state_.layout());  // config::ViewerLayout's order
  if (ImGui::Combo("layout (L)", &layout, layouts, 4))
    state_.setLayout(static_cast<config::ViewerLayout>(layout));
  if (state_.petCtLayout()) colormapCombo(state_, "PET/MIP colours", ColorTarget::Functional);
  const auto modes = ViewerState::modes3d();
  int mode = 0;
  for (int i = 0; i < static_cast<int>(modes.size()); ++i)
    if (modes[static_cast<std::size_t>(i)] == v.mode) mode = i;
  if (ImGui::Combo("3D mode", &mode, kModeLabels, static_cast<int>(modes.size())))
    state_.setMode(modes[static_cast<std::size_t>(mode)]);
  const auto names = mvw::study::presetsFor(state_.anatomical());  // no CT preset on a PET in SUV
  if (ImGui::BeginCombo("preset", state_.presetName().c_str())) {
    for (const auto& n : names)
      if (ImGui::Selectable(n.c_str(), n == state_.presetName())) state_.setPreset(n);
    ImGui::EndCombo();
  }
  // Transfer function points: opacity per point.
  if (ImGui::TreeNode("transfer function points")) {
    for (std::size_t i = 0; i < v.transfer.points.size(); ++i) {
      ImGui::PushID(static_cast<int>(i));
      auto& pt = v.transfer.points[i];
      float value = static_cast<float>(pt.value);
      if (ImGui::DragFloat("value", &value, 1.0f)) pt.value = value, state_.markDirty(k3d);
      if (ImGui::SliderFloat("opacity", &pt.rgba.a, 0.0f, 1.0f)) state_.markDirty(k3d);
      if (ImGui::ColorEdit3("colour", &pt.rgba.r)) state_.markDirty(k3d);
      ImGui::PopID();
    }
    ImGui::TreePop();
  }
  // Sampling quality: the ray step in mm (0 = half the smallest voxel spacing).
  float step = static_cast<float>(v.stepMm);
  if (ImGui::SliderFloat("step mm (0 auto)", &step, 0.0f, 4.0f))
    v.stepMm = step, state_.markDirty(k3d);
  float iso = static_cast<float>(v.iso);
  const auto [lo, hi] = state_.scene().valueRange;
  if (ImGui::SliderFloat("iso value", &iso, float(lo), float(hi)))
    v.iso = iso, state_.markDirty(k3d);
  float w = static_cast<float>(state_.mprWindow().window);
  float l = static_cast<float>(state_.mprWindow().level);
  // `|`, not `||`: both widgets are drawn every frame.
  if (ImGui::DragFloat("MPR window", &w, 2.0f, 1.0f, float(hi - lo) * 2) |
      ImGui::DragFloat("MPR level", &l, 2.0f, float(lo), float(hi)))
    state_.setMprWindow({w, l});
  colormapCombo(state_, "MIP colours", ColorTarget::View3d);
  colormapCombo(state_, "MPR colours", ColorTarget::Mpr);
  if (!state_.study().segmentation) {
  } else if (bool outlines = state_.segmentOutlines();
             ImGui::Checkbox("segment outlines", &outlines)) {
    state_.setSegmentOutlines(outlines);
  }
  // The rotating 3D view, as `mvw render --orbit` (keys O and K).
  const viewer::Orbit orbit = state_.orbit().mode();
  if (ImGui::Button(orbit == viewer::Orbit::Spin ? "stop spin (O)" : "spin (O)"))
    state_.toggleOrbit(viewer::Orbit::Spin);
  ImGui::SameLine();
  if (ImGui::Button(orbit == viewer::Orbit::Rock ? "stop rock (K)" : "rock +-30 (K)"))
    state_.toggleOrbit(viewer::Orbit::Rock);
}

void ViewerPanel::drawDepthCue() {
  render::RenderSettings& v = state_.view3d();
  ImGui::Separator();
  ImGui::Text("depth-cued MIP (Heidrich 1995)");
  bool cue = v.depthCue.on;
  if (ImGui::Checkbox("depth cue", &cue)) v.depthCue.on = cue, state_.markDirty(k3d);
  float b0 = float(v.depthCue.brightness), a = float(v.depthCue.amount),
        b = float(v.depthCue.contrast);
  if (ImGui::SliderFloat("brightness", &b0, 0, 1) | ImGui::SliderFloat("depth cue", &a, 0, 1) |
      ImGui::SliderFloat("contrast", &b, 0, 1)) {
    v.depthCue.brightness = b0, v.depthCue.amount = a, v.depthCue.contrast = b;
    state_.markDirty(k3d);
  }
}

// The functional volume: its overlay, its window, the glyphs and the registration.
void ViewerPanel::drawFunctionalControls() {
  render::RenderSettings& v = state_.view3d();
  ImGui::Separator();
  ImGui::Text("functional volume");
  colormapCombo(state_, "overlay colours", ColorTarget::Overlay);
  float opacity = float(v.overlay.opacity), threshold = float(v.overlay.threshold);
  if (ImGui::SliderFloat("overlay opacity", &opacity, 0, 1) |
      ImGui::SliderFloat("threshold", &threshold, 0, 1)) {
    v.overlay.opacity = opacity, v.overlay.threshold = threshold;
    state_.markAllDirty();
  }
  drawFunctionalWindow();
  drawGlyphControls();
  drawRegistration();
}

// The attribute's mapping to 0..1 (colour map, glyph beta): a window, or label classes.
void ViewerPanel::drawFunctionalWindow() {
  render::RenderSettings& v = state_.view3d();
  const auto [flo, fhi] = state_.scene().functionalRange;
  const auto [wlo, whi] = functionalWindow(v, state_.scene().functionalRange);
  float fw[2] = {float(wlo), float(whi)};
  if (ImGui::DragFloatRange2("attribute", &fw[0], &fw[1], float(fhi - flo) / 200.0f, float(flo),
                             float(fhi)))
    setFunctionalWindow(v, fw[0], fw[1], state_.scene().functionalRange), state_.markAllDirty();
  // The PET/CT layout's functional pane and MIP: the functional volume's own window.
  if (state_.petCtLayout()) {
    const auto [dlo, dhi] = state_.functionalDisplayWindow();
    float dw[2] = {float(dlo), float(dhi)};
    if (ImGui::DragFloatRange2("pane window", &dw[0], &dw[1], float(fhi - flo) / 200.0f,
                               float(std::min(flo, dlo)), float(std::max(fhi, dhi))))
      state_.setFunctionalDisplayWindow(dw[0], dw[1]);
  }
  int classes = v.functionalClasses;
  if (ImGui::InputInt("classes", &classes)) {
    v.functionalClasses = std::clamp(classes, 0, 64);
    state_.markAllDirty();
  }
}

// Glyphs and colour fusion: their switches, spacing and size, the legend, method and kinds.
void ViewerPanel::drawGlyphControls() {
  render::RenderSettings& v = state_.view3d();
  bool glyphs = v.glyphs.on, fusion = v.overlay.fusion;
  if (ImGui::Checkbox("glyphs (G)", &glyphs)) v.glyphs.on = glyphs, state_.markDirty(k3d);
  ImGui::SameLine();
  if (ImGui::Checkbox("colour fusion (F)", &fusion))
    v.overlay.fusion = fusion, state_.markDirty(k3d);
  // A fused minip or average: the functional maximum along the ray, or its mean.
  if (v.overlay.fusion && takesFusionMean(v.mode)) {
    ImGui::SameLine();
    bool mean = v.overlay.projection == render::FusionProjection::Mean;
    if (ImGui::Checkbox("functional mean", &mean)) {
      v.overlay.projection = mean ? render::FusionProjection::Mean : render::FusionProjection::Max;
      state_.markDirty(k3d);
    }
  }
  if (v.glyphMap.placement == render::GlyphPlacement::BlueNoise) {
    // The blue-noise spacing (the diameter follows at its default fraction) and the size range.
    float spacing = float(glyphSpacingMm(v));
    if (ImGui::SliderFloat("glyph spacing mm", &spacing, 2, 30))
      setGlyphSpacingMm(v, spacing), state_.markDirty(k3d);
    float minSize = float(v.glyphs.minSize);
    if (ImGui::SliderFloat("smallest bump", &minSize, 0, 1))
      v.glyphs.minSize = minSize, state_.markDirty(k3d);
  } else {
    float gd = float(v.glyphDiameterMm);
    if (ImGui::SliderFloat("glyph size mm", &gd, 1, 40))
      v.glyphDiameterMm = gd, state_.markDirty(k3d);
  }
  // The legend, as the 3D pane shows it: what each bump size or kind means.
  for (const render::GlyphLegendEntry& e : state_.glyphLegend(k3d, v).entries)
    ImGui::BulletText("%s", glyphLegendLine(e).c_str());
  int method = static_cast<int>(v.glyphs.method);  // the enum's order is the list's
  const char* methods[] = {"sized (eqs. 2-3)", "simple (eq. 1)"};
  if (ImGui::Combo("glyph method", &method, methods, 2))
    v.glyphs.method = static_cast<GlyphMethod>(method), state_.markDirty(k3d);
  const char* convexity[] = {"convex", "concave", "both"};
  int convex = static_cast<int>(v.glyphs.convexity);  // the enum's order is the list's
  if (ImGui::Combo("bumps", &convex, convexity, 3)) {
    v.glyphs.convexity = static_cast<GlyphConvexity>(convex);
    state_.markDirty(k3d);
  }
  if (state_.study().functionalKind == config::FunctionalKind::Labels) glyphLabelPicker(state_);
}

// How the functional volume is placed, and the button that registers it again.
void ViewerPanel::drawRegistration() {
  ViewerRegistration& registration = state_.registration();
  ImGui::TextWrapped("%s", registrationLine(registration.description()).c_str());
  if (registration.running())
    ImGui::Text("registering (mutual information)... %.1f s", registration.seconds());
  else if (ImGui::Button(rerunRegistrationLabel(registration.method()).c_str()))
    registration.start();
}

void ViewerPanel::drawCrosshair() {
  ImGui::Separator();
  const glm::dvec3 c = state_.crosshair();
  ImGui::Text("crosshair %.1f, %.1f, %.1f mm (LPS)", c.x, c.y, c.z);
  if (const auto cursor = state_.cursor()) {
    const glm::dvec3& at = cursor->second;
    ImGui::Text("cursor %.1f, %.1f, %.1f mm (LPS)", at.x, at.y, at.z);
    ImGui::TextWrapped("%s", state_.readout(at).c_str());
  }
}

// Measurements on the MPR panes: the mouse tool, the spheres' statistics, the rulers.
void ViewerPanel::drawMeasurementControls() {
  const Volume& anatomical = state_.anatomical();
  const Volume* functional = state_.functional();
  ImGui::Separator();
  ViewerMeasurements& measurements = state_.measurements();
  int tool = static_cast<int>(measurements.tool());
  ImGui::Text("MPR mouse");
  const char* tools[] = {"crosshair", "sphere ROI", "ruler"};
  for (int t = 0; t < 3; ++t) {  // on a line of their own: beside the label "ruler" was cut
    if (t > 0) ImGui::SameLine();
    if (ImGui::RadioButton(tools[t], &tool, t)) measurements.setTool(static_cast<MprTool>(tool));
  }
  const auto& spheres = measurements.all().spheres;
  const auto& stats = measurements.sphereStatistics();
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    ImGui::TextColored(ImVec4(0.3f, 1.0f, 0.5f, 1.0f), "%s", sphereHeader(i, spheres[i]).c_str());
    statsLine(ViewerState::volumeName(anatomical, "anatomical"), stats[i].anatomical,
              stats[i].anatomicalProblem);
    if (functional)
      statsLine(ViewerState::volumeName(*functional, "functional"), stats[i].functional,
                stats[i].functionalProblem);
  }
  const auto& rulers = measurements.all().rulers;
  for (std::size_t i = 0; i < rulers.size(); ++i)
    ImGui::TextColored(ImVec4(1.0f, 0.86f, 0.25f, 1.0f), "%s",
                       rulerLine(i, ViewerMeasurements::rulerLengthMm(rulers[i])).c_str());
  if ((!spheres.empty() || !rulers.empty()) && ImGui::Button("clear measurements"))
    measurements.clear();
}

// The mouse and the keys, and what the last request said (a screenshot written, a state saved).
void ViewerPanel::drawHelp() {
  ImGui::Separator();
  ImGui::TextWrapped(
      "Mouse: 3D left-drag rotate, right-drag zoom, middle-drag pan, wheel zoom. MPR: left "
      "click/drag moves the crosshair, wheel scrolls slices, Ctrl+wheel zooms and middle-drag "
      "pans (the MPR panes together), right-drag or Ctrl-drag "
      "window/level, Shift-drag a sphere ROI, Alt-drag a ruler. Double-click maximises a "
      "view.\nKeys: 1-5 modes, D depth cue, G glyphs, F "
      "fusion, P next preset, O spin, K rock, Z fit the MPR panes, C centre them on the crosshair, "
      "J jump to the hottest voxel, segments, ROIs, L next layout (PET/CT), "
      "X one screen pixel per "
      "voxel, R reset, S screenshot, Ctrl+S save state as a study config.");
  if (const std::string& status = state_.requests().status(); !status.empty())
    ImGui::TextWrapped("%s", status.c_str());
}

bool ViewerPanel::draw() {
  dragging_ = false;
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("mvw", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoScrollWithMouse);
  const float panel = 340.0f * scale_;
  ImGui::BeginChild("panel", ImVec2(panel, 0), true);
  drawControls();
  ImGui::EndChild();
  const ImVec2 origin(panel + 12.0f, 8.0f);
  const ImVec2 area(io.DisplaySize.x - origin.x - 8.0f, io.DisplaySize.y - 16.0f);
  if (state_.maximised() >= 0) {
    drawPane(state_.maximised(), origin, area);
  } else {
    const ImVec2 cell(area.x / 2 - 2, area.y / 2 - 2);
    for (int p = 0; p < kPaneCount; ++p) {
      const int at = state_.paneCell(p);  // the PET/CT layout puts its panes in reading order
      drawPane(p, ImVec2(origin.x + (at % 2) * (cell.x + 4), origin.y + (at / 2) * (cell.y + 4)),
               cell);
    }
  }
  ImGui::End();
  if (!io.WantTextInput) {
    // GLFW's key codes for digits and letters are their ASCII upper-case characters.
    for (int key : {GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5, GLFW_KEY_D,
                    GLFW_KEY_G, GLFW_KEY_F, GLFW_KEY_P, GLFW_KEY_R, GLFW_KEY_S, GLFW_KEY_O,
                    GLFW_KEY_K, GLFW_KEY_Z, GLFW_KEY_X, GLFW_KEY_C, GLFW_KEY_J, GLFW_KEY_L})
      if (ImGui::IsKeyPressed(key, false)) state_.key(static_cast<char>(key), io.KeyCtrl);
  }
  return dragging_;
}

}  // namespace mvw::app
