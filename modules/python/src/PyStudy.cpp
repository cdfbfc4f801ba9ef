#include "PyStudy.h"

#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <nlohmann/json.hpp>

#include "GlThread.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/Png.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/output/StudyRender.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Session.h"

namespace py = pybind11;

namespace mvw::python {

namespace {

namespace fs = std::filesystem;

// A study loaded and attached to a renderer, as `mvw render` holds it (output::renderStudy):
// the renderer and its context live on the GL thread (GlThread.h).
class Study {
 public:
  Study(config::StudyConfig config, const std::string& gl, const std::string& gradient) {
    const render::GradientSource source = render::parseGradientSource(gradient);
    session_ = std::make_unique<study::Session>(std::move(config));
    py::gil_scoped_release released;
    // In renderStudy's order: the context before the volumes (a --gl this machine cannot give
    // fails in milliseconds), the volumes, then the renderer.
    onGlThread([&] {
      context_ = output::makeHeadlessContext(gl);
      // The GL functions are loaded for the context made last (render::GlContext), and OSMesa
      // and EGL are separate libraries: one backend at a time in a process.
      Backends& live = liveBackends();
      if (live.count > 0 && live.name != context_->backend()) {
        const std::string made = context_->backend();
        context_.reset();
        throw py::value_error("mvw.Study: this process renders with " + live.name +
                              " while a Study on it lives, and this one would use " + made +
                              ": one GL backend at a time (delete the others first, or give "
                              "gl='" +
                              live.name + "')");
      }
      live.name = context_->backend();
      ++live.count;
    });
    try {
      session_->load(pacs::Options{});
      onGlThread([&] {
        context_->makeCurrent();
        renderer_ =
            std::make_unique<render::VolumeRenderer>(*context_, session_->anatomical(), source);
        session_->attach(*renderer_);
        planned_ = session_->views(*renderer_);
      });
    } catch (...) {
      release();
      throw;
    }
  }
  Study(const Study&) = delete;
  Study& operator=(const Study&) = delete;
  // With the GIL held (the GL thread never takes it): a destructor that released it could run
  // during the interpreter's finalisation.
  ~Study() { release(); }

  std::string backend() const { return context_->backend(); }

  std::vector<std::string> viewNames() const {
    std::vector<std::string> names;
    for (const study::PlannedView& v : planned_) names.push_back(v.config.name);
    return names;
  }

  // The view asked for: the config's first (None), one of its views by name, or a view object.
  py::array render(const py::object& view, const std::optional<int>& size) {
    if (size && (*size < 1 || *size > 8192))
      throw py::value_error("mvw.Study.render: size is 1 to 8192 pixels, not " +
                            std::to_string(*size));
    std::vector<config::ViewConfig> views;
    for (const study::PlannedView& v : planned_) views.push_back(v.config);
    std::size_t index = 0;
    if (py::isinstance<py::dict>(view)) {
      const nlohmann::json j = nlohmann::json::parse(
          py::module_::import("json").attr("dumps")(view).cast<std::string>());
      const int n = static_cast<int>(views.size());
      views.push_back(config::parseViewConfig(j, session_->config().file, "the view given", n));
      index = views.size() - 1;
    } else if (py::isinstance<py::str>(view)) {
      const std::string name = view.cast<std::string>();
      while (index < views.size() && views[index].name != name) ++index;
      if (index == views.size()) {
        std::string known;
        for (const config::ViewConfig& v : views) known += (known.empty() ? "" : ", ") + v.name;
        throw py::value_error("mvw.Study.render: the study has no view '" + name +
                              "' (its views: " + known + ")");
      }
    } else if (!view.is_none()) {
      throw py::type_error(
          "mvw.Study.render: view is a view's name (str), a view object (dict) or None, not " +
          py::str(py::type::of(view).attr("__name__")).cast<std::string>());
    }
    Image image;
    {
      py::gil_scoped_release released;
      onGlThread([&] {
        // The config's views as planned (the same settings `mvw render` renders), or planned
        // anew over the loaded volumes with the view given or the size (--size).
        std::vector<study::PlannedView> planned;
        if (index >= planned_.size() || size) {
          study::ViewOverrides overrides;
          overrides.size = size;
          planned = session_->views(views, overrides, renderer_->functionalRange());
        }
        const study::PlannedView& v = planned.empty() ? planned_[index] : planned[index];
        context_->makeCurrent();  // the painter draws after the renderer, in the same context
        image = output::viewPainter(*renderer_, *session_, v)(v.settings).image;
      });
    }
    return imageArray(image);
  }

  static py::array imageArray(const Image& image) {
    py::array_t<std::uint8_t> out({image.height, image.width, 4});
    std::memcpy(out.mutable_data(), image.rgba.data(), image.rgba.size());
    return out;
  }

 private:
  // The renderer and its context go on the thread that made them.
  void release() {
    if (!renderer_ && !context_) return;
    onGlThread([this] {
      // The renderer deletes its GL objects in the current context: its own, not another
      // Study's (GL names are numbers from 1 in every context: another's textures would go).
      if (context_) context_->makeCurrent();
      renderer_.reset();
      if (context_) --liveBackends().count;
      context_.reset();
    });
  }

  // The backend of the contexts alive (on the GL thread only).
  struct Backends {
    std::string name;
    int count = 0;
  };
  static Backends& liveBackends() {
    static Backends live;
    return live;
  }

  std::unique_ptr<study::Session> session_;
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<render::VolumeRenderer> renderer_;
  std::vector<study::PlannedView> planned_;
};

std::unique_ptr<Study> makeStudy(const py::object& config, const std::optional<std::string>& gl,
                                 const std::string& gradient) {
  if (gradient != "auto" && gradient != "texture" && gradient != "shader")
    throw py::value_error("mvw.Study: gradient is auto, texture or shader, not '" + gradient + "'");
  if (gl && !render::parseGlRequest(*gl))
    throw py::value_error(std::string("mvw.Study: gl is one of ") + render::kGlRequestNames +
                          ", not '" + *gl + "'");
  if (py::isinstance<py::dict>(config)) {
    // Paths in the dict are relative to the working folder; messages name the dict so.
    const nlohmann::json j = nlohmann::json::parse(
        py::module_::import("json").attr("dumps")(config).cast<std::string>());
    return std::make_unique<Study>(
        config::studyConfigFromJson(j, fs::current_path() / "<study dict>"), gl.value_or(""),
        gradient);
  }
  if (!py::isinstance<py::str>(config) &&
      !py::isinstance(config, py::module_::import("os").attr("PathLike")))
    throw py::type_error(
        "mvw.Study: config is a study config's path (str or os.PathLike) or a dict, not " +
        py::str(py::type::of(config).attr("__name__")).cast<std::string>());
  const fs::path path = config.cast<fs::path>();
  return std::make_unique<Study>(config::loadStudyConfig(path), gl.value_or(""), gradient);
}

}  // namespace

void bindStudy(py::module_& m) {
  py::class_<Study> cls(m, "Study", R"doc(
A study config (the JSON `mvw render`, `mvw view` and `mvw validate` read) loaded for
rendering: its volumes read, placed and handed to a headless GL context chosen as `mvw render`
chooses it (gl: the --gl option, else $MVW_GL, else auto: an EGL GPU device, Mesa's EGL
surfaceless platform, Mesa's EGL software device, OSMesa).

    study = mvw.Study("sample_configs/cranium_ct.json")   # or a dict of the same keys
    study.views                                          # the config's view names
    rgba = study.render("bone")                          # (H, W, 4) uint8, as bone.png

Renders are made on one GL thread of the module: renders from several Python threads are
serialised, and the others run while one renders.)doc");
  cls.def(py::init(&makeStudy), py::arg("config"), py::kw_only(), py::arg("gl") = py::none(),
          py::arg("gradient") = "auto", R"doc(
config:   a study config's path, or a dict of its keys (relative paths from the working folder).
gl:       auto, egl, egl-device, egl-surfaceless or osmesa (None: $MVW_GL, else auto).
gradient: auto, texture or shader: where shading takes its gradient (--gradient).
Raises mvw.InputError naming the config or the volume that cannot be used, mvw.ServiceError for
a PACS series that cannot be retrieved.)doc");
  cls.def_property_readonly("views", &Study::viewNames,
                            "The names of the config's views, in its order.");
  cls.def_property_readonly("gl_backend", &Study::backend,
                            "The headless GL it renders with: egl-device, egl-surfaceless or "
                            "osmesa (render.json's gl_backend).");
  cls.def("render", &Study::render, py::arg("view") = py::none(), py::arg("size") = py::none(),
          R"doc(
One view as an image: a NumPy array (height, width, 4) of uint8, RGBA, row 0 at the top: the
pixels `mvw render` writes into VIEW.png for the same view and size (annotations included
where the view annotates). An orbiting view gives its first frame.

view: a view's name, a view object (a dict of the keys of a config's "render.views" entry), or
    None for the config's first view.
size: width and height in pixels, as `mvw render --size`; None: the view's own.

Alpha is 255 everywhere, as in the PNG: every mode composites the volume over the view's
background colour, so no transparency is left; image[..., :3] is the RGB image.)doc");
  m.def(
      "read_png",
      [](const fs::path& path) {
        Image image;
        {
          py::gil_scoped_release released;
          image = io::readPng(path);
        }
        return Study::imageArray(image);
      },
      py::arg("path"), R"doc(
A PNG as a NumPy array (height, width, 4) of uint8, RGBA, row 0 at the top, read as mvw reads
PNGs (grey into R, G and B; alpha 255 where the file has none; 16-bit samples' high byte):
a render of `mvw render`, compared with mvw.Study.render's.)doc");
}

}  // namespace mvw::python
