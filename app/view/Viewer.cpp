#include "Viewer.h"

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <glm/common.hpp>

#include "GlfwContext.h"
#include "PacsPanel.h"
#include "ViewerPanel.h"
#include "mvw/core/Error.h"
#include "mvw/io/Png.h"
#include "mvw/render/DisplayTexture.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/render/WindowFramebuffer.h"
#include "mvw/study/Session.h"
#include "mvw/viewer/OpenedStudy.h"
#include "mvw/viewer/PacsBrowser.h"
#include "mvw/viewer/PanelText.h"
#include "mvw/viewer/ViewerFrames.h"
#include "mvw/viewer/ViewerScript.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::app {

// The window draws the window-free viewer (mvw::viewer) and acts through it throughout.
using namespace mvw::viewer;

namespace {

// Dear ImGui with its GLFW and OpenGL3 backends for one window, shut down however the loop
// ends (an exception from the script included). The OpenGL3 backend loads its own few GL
// functions, so it needs no loader from us.
class ImGuiSession {
 public:
  ImGuiSession(GLFWwindow* window, float scale) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().ScaleAllSizes(scale);
    ImGui::GetIO().FontGlobalScale = scale;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;
};

// What the 3D pane's render of a frame took and at what size (frame log).
struct Render3d {
  double milliseconds = 0.0;
  glm::ivec2 size{0};
};

// segments: the study's segmentation (null: none), whose legend the MPR panes show with the
// outlines. Each pane is annotated by `mvw render`'s painter (output::drawAnnotations).
// functionalRenderer: a renderer of the functional volume, made on first use, for the panes
// that show it as their image (the PET/CT layout's MIP).
Render3d renderDirtyPanes(ViewerState& state, render::VolumeRenderer& renderer,
                          const std::function<render::VolumeRenderer&()>& functionalRenderer,
                          const mvw::study::SegmentOverlay* segments,
                          ViewerPanel::PaneTextures& textures, bool interacting) {
  Render3d rendered3d;
  for (int p = 0; p < kPaneCount; ++p) {
    if (!state.needsRender(p)) continue;
    const render::RenderSettings s = state.renderSettings(p, interacting);
    render::RenderedFrame f =
        (state.paneShowsFunctional(p) ? functionalRenderer() : renderer).render(s);
    if (p == k3d) rendered3d = {f.milliseconds, s.size};
    Image shown = f.image;
    output::ViewAnnotations a = paneAnnotations(state, p, s, renderer.functionalRange(), segments);
    output::drawAnnotations(shown, f.camera, s, a, renderer);
    textures[static_cast<std::size_t>(p)].upload(shown);
    state.rendered(p, f.camera, std::move(f.image), interacting, f.milliseconds);
  }
  return rendered3d;
}

// One open study and what shows it: the session (its volumes), the renderer holding them in GL,
// the panes' textures, the state and the panel. Opening a study from the PACS replaces the
// whole of it; the window, ImGui and the PACS browser stay. Members are destroyed in reverse:
// the panel, then the state (a running registration, which reads the volumes, is waited for),
// the GL objects while the context still exists, the volumes last.
class OpenStudy {
 public:
  OpenStudy(GlfwContext& context, std::unique_ptr<mvw::study::Session> loaded, float scale)
      : session_(std::move(loaded)), renderer_(context, session_->anatomical()) {
    const mvw::study::Session& session = *session_;
    const Volume* functional = session.functional();
    session.attach(renderer_);
    state_ = std::make_unique<ViewerState>(session.config(), session.anatomical(), functional,
                                           studyScene(session, renderer_));
    panel_ = std::make_unique<ViewerPanel>(*state_, textures_, scale);
    // The functional volume as an image of its own (the PET/CT layout's MIP), uploaded once
    // the layout first asks for it.
    functionalRenderer_ = [this, &context, functional]() -> render::VolumeRenderer& {
      if (!functionalRendererHeld_)
        functionalRendererHeld_ = std::make_unique<render::VolumeRenderer>(context, *functional);
      return *functionalRendererHeld_;
    };
  }
  OpenStudy(const OpenStudy&) = delete;
  OpenStudy& operator=(const OpenStudy&) = delete;

  const mvw::study::Session& session() const { return *session_; }
  render::VolumeRenderer& renderer() { return renderer_; }
  ViewerState& state() { return *state_; }
  ViewerPanel& panel() { return *panel_; }
  ViewerPanel::PaneTextures& textures() { return textures_; }
  const std::function<render::VolumeRenderer&()>& functionalRenderer() const {
    return functionalRenderer_;
  }

 private:
  std::unique_ptr<mvw::study::Session> session_;
  render::VolumeRenderer renderer_;
  ViewerPanel::PaneTextures textures_;
  std::unique_ptr<render::VolumeRenderer> functionalRendererHeld_;
  std::function<render::VolumeRenderer&()> functionalRenderer_;
  std::unique_ptr<ViewerState> state_;
  std::unique_ptr<ViewerPanel> panel_;
};

// The window without a study (mvw view with PACS servers and nothing to open yet): what to do.
void drawNoStudy(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("mvw", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::BeginChild("panel", ImVec2(340.0f * scale, 0), true);
  ImGui::TextWrapped(
      "No study open. Choose one in the PACS window, or start mvw view with a "
      "study config (mvw view STUDY.json).");
  ImGui::EndChild();
  ImGui::End();
}

}  // namespace

int runViewer(ViewerOptions options) {
  // Read and checked before the window opens: a typo in a script is bad input, not a crash.
  ViewerScript script;
  if (!options.script.empty()) script = ViewerScript::load(options.script);
  // The frame log is opened before the window: a path that cannot be written is reported as
  // bad input with nothing drawn.
  FrameLog frameLog(options.frameLog);
  const float scale = static_cast<float>(options.uiScale);
  // The PACS browser outlives every study it opens (declared before them: a running retrieve
  // is joined after the study's GL objects are gone, before the window closes).
  GlfwContext context(glm::ivec2(options.width, options.height), "mvw view");
  ImGuiSession imgui(context.window(), scale);
  render::WindowFramebuffer framebuffer(context);
  PacsBrowser browser(options.pacs);
  browser.setServers(std::move(options.launch.servers), options.launch.serversFile,
                     options.launch.serversProblem);
  PacsPanel pacsPanel(browser, scale);
  std::unique_ptr<OpenStudy> open;
  if (options.launch.session)
    open = std::make_unique<OpenStudy>(context, std::move(options.launch.session), scale);
  pacsPanel.setVisible(!open);
  auto showPacs = [&pacsPanel] { pacsPanel.setVisible(true); };
  // The window's title names the study shown (one opened from the PACS names its server).
  auto shown = [&] {
    open->panel().setOpenPacs(showPacs);
    glfwSetWindowTitle(context.window(), viewerTitle(open->session().config().name).c_str());
  };
  if (open) shown();

  frameLog.start();
  int frames = 0;
  bool quit = false;
  while (!glfwWindowShouldClose(context.window()) && !quit &&
         !(open && open->state().requests().quitRequested())) {
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    // A study retrieved and loaded from the PACS takes the current one's place; one the GL
    // side cannot take (a volume too large for a texture) leaves the current study shown and
    // says why in the PACS window.
    if (std::unique_ptr<mvw::study::Session> loaded = browser.poll()) {
      try {
        auto next = std::make_unique<OpenStudy>(context, std::move(loaded), scale);
        open.reset();  // the old study's GL objects go before the new one's first frame
        open = std::move(next);
        shown();
        pacsPanel.setVisible(false);
        browser.takeWindowRequest();  // the open's own request: the window has done its job
      } catch (const Error& e) {
        browser.fail(e.what());
      }
    }
    bool dragging = false;
    Render3d rendered3d;
    int divisor = 0;
    if (open) {
      ViewerState& state = open->state();
      if (auto anatomicalFromFunctional = state.finishRegistration())
        open->session().attach(open->renderer(), *anatomicalFromFunctional);
      dragging = open->panel().draw() || state.requests().scriptedInteraction();
      divisor = state.dragDivisor();  // the one this frame renders with
      state.advanceOrbit();           // one step per drawn frame while the 3D view spins or rocks
    } else {
      drawNoStudy(scale);
    }
    if (browser.takeWindowRequest()) pacsPanel.setVisible(true);
    pacsPanel.draw(340.0f * scale);
    if (open)
      rendered3d = renderDirtyPanes(open->state(), open->renderer(), open->functionalRenderer(),
                                    open->session().segments(), open->textures(), dragging);
    ImGui::Render();
    framebuffer.clear({0.08f, 0.08f, 0.1f, 1.0f});
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    // Scripts act on a frame that is fully drawn; so do screenshots (the back buffer).
    if (!script.empty() && frames > 1 && !script.step(open ? &open->state() : nullptr, &browser)) {
      if (open)
        open->state().requests().requestQuit();
      else
        quit = true;
    }
    if (auto file = script.idleRequests().takeScreenshotRequest())
      io::writePng(framebuffer.read(), *file);  // asked while no study was open
    if (open) {
      ViewerState& state = open->state();
      if (auto file = state.requests().takeScreenshotRequest()) {
        io::writePng(framebuffer.read(), *file);
        state.requests().setStatus("saved " + file->string());
      }
      if (auto shot = state.requests().takePaneScreenshotRequest())
        io::writePng(paneImage(framebuffer.read(), state.paneOrigin(shot->first),
                               state.paneSize(shot->first)),
                     shot->second);
    }
    glfwSwapBuffers(context.window());
    frameLog.frame(frames, rendered3d.milliseconds, rendered3d.size, dragging, divisor);
    ++frames;
    const bool idle =
        !open || (!open->state().anyDirty() && !open->state().registration().running());
    if (idle && script.empty())
      glfwWaitEventsTimeout(0.05);  // idle: no busy loop (a PACS step's time still ticks on)
  }
  return 0;
}

}  // namespace mvw::app
