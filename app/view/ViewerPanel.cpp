#include "ViewerPanel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "mvw/core/GlyphDefaults.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/TransferFunction.h"

namespace mvw::app {

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
}  // namespace

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
  if (ImGui::IsItemHovered()) {
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) state_.toggleMaximised(pane);
    if (io.MouseWheel != 0.0f) state_.wheel(pane, io.MouseWheel);
    if (pane != k3d && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.KeyCtrl)
      state_.click(pane, fx, fy);
    if (pane != k3d) {
      hoverWorld_ = state_.onPlane(pane, fx, fy);
      hoverValid_ = true;
    }
  }
  for (int b = 0; b < 3; ++b)
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(b, 0.0f)) {
      const ImVec2 d = io.MouseDelta;
      if (d.x != 0 || d.y != 0) {
        if (pane != k3d && b == 0 && !io.KeyCtrl)
          state_.click(pane, fx, fy);
        else
          state_.drag(pane, d.x / size.x, d.y / size.y, static_cast<MouseButton>(b), io.KeyCtrl);
        dragging_ = true;
      }
    }
  if (pane != k3d && !texture.empty()) {  // the linked crosshair
    const glm::dvec4 c =
        state_.paneCamera(pane).clipFromWorld * glm::dvec4(state_.crosshair(), 1.0);
    const float cx = pos.x + static_cast<float>((c.x / c.w + 1) * 0.5) * size.x;
    const float cy = pos.y + static_cast<float>((1 - c.y / c.w) * 0.5) * size.y;
    draw->AddLine(ImVec2(cx, pos.y), ImVec2(cx, pos.y + size.y), IM_COL32(80, 200, 255, 160));
    draw->AddLine(ImVec2(pos.x, cy), ImVec2(pos.x + size.x, cy), IM_COL32(80, 200, 255, 160));
  }
  ImGui::PopID();
}

void ViewerPanel::drawControls() {
  render::RenderSettings& v = state_.view3d();
  const Volume& anatomical = state_.anatomical();
  const Volume* functional = state_.functional();
  ImGui::Text("%s", state_.study().name.empty() ? "mvw view" : state_.study().name.c_str());
  ImGui::Separator();
  const auto modes = ViewerState::modes3d();
  int mode = 0;
  for (int i = 0; i < static_cast<int>(modes.size()); ++i)
    if (modes[static_cast<std::size_t>(i)] == v.mode) mode = i;
  if (ImGui::Combo("3D mode", &mode, kModeLabels, static_cast<int>(modes.size())))
    state_.setMode(modes[static_cast<std::size_t>(mode)]);
  const auto names = render::transferPresetNames();
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
  float iso = static_cast<float>(v.isoValue);
  const auto [lo, hi] = state_.scene().valueRange;
  if (ImGui::SliderFloat("iso value", &iso, float(lo), float(hi)))
    v.isoValue = iso, state_.markDirty(k3d);
  float w = static_cast<float>(state_.mprWindow()), l = static_cast<float>(state_.mprLevel());
  // `|`, not `||`: both widgets are drawn every frame.
  if (ImGui::DragFloat("MPR window", &w, 2.0f, 1.0f, float(hi - lo) * 2) |
      ImGui::DragFloat("MPR level", &l, 2.0f, float(lo), float(hi)))
    state_.setMprWindow(w, l);
  colormapCombo(state_, "MIP colours", ColorTarget::View3d);
  colormapCombo(state_, "MPR colours", ColorTarget::Mpr);
  // The rotating 3D view, as `mvw render --orbit` (keys O and K).
  const Orbit orbit = state_.orbit();
  if (ImGui::Button(orbit == Orbit::Spin ? "stop spin (O)" : "spin (O)"))
    state_.toggleOrbit(Orbit::Spin);
  ImGui::SameLine();
  if (ImGui::Button(orbit == Orbit::Rock ? "stop rock (K)" : "rock +-30 (K)"))
    state_.toggleOrbit(Orbit::Rock);
  ImGui::Separator();
  ImGui::Text("depth-cued MIP (Heidrich 1995)");
  bool cue = v.depthCue;
  if (ImGui::Checkbox("depth cue", &cue)) v.depthCue = cue, state_.markDirty(k3d);
  float b0 = float(v.cueBrightness), a = float(v.cueAmount), b = float(v.cueContrast);
  if (ImGui::SliderFloat("brightness", &b0, 0, 1) | ImGui::SliderFloat("depth cue", &a, 0, 1) |
      ImGui::SliderFloat("contrast", &b, 0, 1)) {
    v.cueBrightness = b0, v.cueAmount = a, v.cueContrast = b;
    state_.markDirty(k3d);
  }
  if (functional) {
    ImGui::Separator();
    ImGui::Text("functional volume");
    colormapCombo(state_, "overlay colours", ColorTarget::Overlay);
    if (ImGui::SliderFloat("overlay opacity", &v.overlayOpacity, 0, 1) |
        ImGui::SliderFloat("threshold", &v.overlayThreshold, 0, 1))
      state_.markAllDirty();
    // The attribute's mapping to 0..1 (colour map, glyph beta): a window, or label classes.
    const auto [flo, fhi] = state_.scene().functionalRange;
    const bool userWindow = v.functionalHigh > v.functionalLow;
    float fw[2] = {float(userWindow ? v.functionalLow : flo),
                   float(userWindow ? v.functionalHigh : fhi)};
    if (ImGui::DragFloatRange2("attribute", &fw[0], &fw[1], float(fhi - flo) / 200.0f, float(flo),
                               float(fhi))) {
      v.functionalLow = fw[0];
      v.functionalHigh = std::max(double(fw[1]), double(fw[0]) + 1e-6 * (fhi - flo));
      state_.markAllDirty();
    }
    int classes = v.functionalClasses;
    if (ImGui::InputInt("classes", &classes)) {
      v.functionalClasses = std::clamp(classes, 0, 64);
      state_.markAllDirty();
    }
    bool glyphs = v.glyphs, fusion = v.fusion;
    if (ImGui::Checkbox("glyphs (G)", &glyphs)) v.glyphs = glyphs, state_.markDirty(k3d);
    ImGui::SameLine();
    if (ImGui::Checkbox("colour fusion (F)", &fusion)) v.fusion = fusion, state_.markDirty(k3d);
    if (v.glyphMap.placement == render::GlyphPlacement::BlueNoise) {
      // The blue-noise spacing (the diameter follows at its default fraction) and the size range.
      float spacing = float(render::blueNoiseSpacing(v.glyphMap.size) * v.glyphDiameterMm /
                            v.glyphMap.diameter);
      if (ImGui::SliderFloat("glyph spacing mm", &spacing, 2, 30)) {
        v.glyphDiameterMm = kBlueNoiseDiameterFraction * spacing;
        v.glyphMap = render::blueNoiseGlyphMap(spacing, v.glyphDiameterMm, v.glyphMap.seed);
        state_.markDirty(k3d);
      }
      float minSize = float(v.glyphMinSize);
      if (ImGui::SliderFloat("smallest bump", &minSize, 0, 1))
        v.glyphMinSize = minSize, state_.markDirty(k3d);
    } else {
      float gd = float(v.glyphDiameterMm);
      if (ImGui::SliderFloat("glyph size mm", &gd, 1, 40))
        v.glyphDiameterMm = gd, state_.markDirty(k3d);
    }
    // The legend, as the 3D pane shows it: what each bump size or kind means.
    for (const render::GlyphLegendEntry& e : state_.glyphLegend(k3d, v).entries)
      ImGui::BulletText("%s  %s", e.label.c_str(),
                        e.size <= 0 ? "no glyph"
                                    : (std::to_string(int(std::lround(100 * e.size))) + " % " +
                                       (e.dimple ? "dimple" : "bump"))
                                          .c_str());
    int method = v.glyphSizeControl ? 0 : 1;
    const char* methods[] = {"sized (eqs. 2-3)", "simple (eq. 1)"};
    if (ImGui::Combo("glyph method", &method, methods, 2))
      v.glyphSizeControl = method == 0, state_.markDirty(k3d);
    const char* convexity[] = {"convex", "concave", "both"};
    int convex = static_cast<int>(v.glyphConvexity);  // the enum's order is the list's
    if (ImGui::Combo("bumps", &convex, convexity, 3)) {
      v.glyphConvexity = static_cast<GlyphConvexity>(convex);
      state_.markDirty(k3d);
    }
    const std::string& registration = state_.registration();
    ImGui::TextWrapped("registration: %s",
                       registration == "none" ? "none (world coordinates)" : registration.c_str());
    if (state_.registering())
      ImGui::Text("registering (mutual information)... %.1f s", state_.registrationSeconds());
    else if (ImGui::Button("re-run registration (rigid MI)"))
      state_.startRegistration();
  }
  ImGui::Separator();
  const glm::dvec3 c = state_.crosshair();
  ImGui::Text("crosshair %.1f, %.1f, %.1f mm (LPS)", c.x, c.y, c.z);
  if (hoverValid_) {
    const ViewerProbe probe = state_.probe(hoverWorld_);
    const std::string value =
        probe.anatomicalInside
            ? std::to_string(static_cast<long long>(std::lround(probe.anatomical))) + " " +
                  anatomical.metadata().unit
            : "outside";
    ImGui::Text("cursor %.1f, %.1f, %.1f: %s", hoverWorld_.x, hoverWorld_.y, hoverWorld_.z,
                value.c_str());
    if (functional && probe.functionalInside)
      ImGui::Text("functional %.4g %s", probe.functional, functional->metadata().unit.c_str());
  }
  ImGui::Separator();
  ImGui::TextWrapped(
      "Mouse: 3D left-drag rotate, right-drag zoom, middle-drag pan, wheel zoom. MPR: left "
      "click/drag moves the crosshair, wheel scrolls slices, right-drag or Ctrl-drag "
      "window/level. Double-click maximises a view.\nKeys: 1-5 modes, D depth cue, G glyphs, F "
      "fusion, P next preset, O spin, K rock, R reset, S screenshot, Ctrl+S save state as a "
      "study config.");
  if (!state_.status().empty()) ImGui::TextWrapped("%s", state_.status().c_str());
}

bool ViewerPanel::draw() {
  dragging_ = false;
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("mvw", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoScrollWithMouse);
  const float panel = 340.0f;
  ImGui::BeginChild("panel", ImVec2(panel, 0), true);
  drawControls();
  ImGui::EndChild();
  const ImVec2 origin(panel + 12.0f, 8.0f);
  const ImVec2 area(io.DisplaySize.x - origin.x - 8.0f, io.DisplaySize.y - 16.0f);
  hoverValid_ = false;  // the panes drawn below say where the cursor is this frame
  if (state_.maximised() >= 0) {
    drawPane(state_.maximised(), origin, area);
  } else {
    const ImVec2 cell(area.x / 2 - 2, area.y / 2 - 2);
    for (int p = 0; p < kPaneCount; ++p)
      drawPane(p, ImVec2(origin.x + (p % 2) * (cell.x + 4), origin.y + (p / 2) * (cell.y + 4)),
               cell);
  }
  ImGui::End();
  if (!io.WantTextInput) {
    // GLFW's key codes for digits and letters are their ASCII upper-case characters.
    for (int key :
         {GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5, GLFW_KEY_D, GLFW_KEY_G,
          GLFW_KEY_F, GLFW_KEY_P, GLFW_KEY_R, GLFW_KEY_S, GLFW_KEY_O, GLFW_KEY_K})
      if (ImGui::IsKeyPressed(key, false)) state_.key(static_cast<char>(key), io.KeyCtrl);
  }
  return dragging_;
}

}  // namespace mvw::app
