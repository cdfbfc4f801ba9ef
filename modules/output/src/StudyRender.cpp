#include "mvw/output/StudyRender.h"

#include <cstdio>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "RenderRecord.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/dicomout/SecondaryCapture.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/MovieWriter.h"
#include "mvw/io/Png.h"
#include "mvw/io/StagedFolder.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/output/OutputFolder.h"
#include "mvw/output/ViewAnnotations.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Caption.h"
#include "mvw/study/Session.h"

namespace mvw::output {

namespace {

namespace fs = std::filesystem;

std::string frameName(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame-%03d.png", k);
  return buf;
}

// The rest of an orbit's frames (frame 0 is the still itself, at the view's own azimuth),
// written with the movie into the staging folder; returns render.json's "orbit" record.
nlohmann::json renderOrbit(const ViewPainter& paint, const render::RenderedFrame& still,
                           io::StagedFolder& staging, std::vector<Image>* keep) {
  const config::ViewConfig& c = paint.view.config;
  const fs::path folder = staging.path() / c.name;
  fs::create_directories(folder);
  const std::string movieName = c.name + ".mp4";
  io::MovieWriter movie(staging.path() / movieName, still.image.width, still.image.height,
                        c.orbit.fps);
  const std::vector<double> azimuths = orbitAzimuths(c.orbit, c.azimuth);
  nlohmann::json files = nlohmann::json::array();
  double ms = still.milliseconds;
  for (std::size_t k = 0; k < azimuths.size(); ++k) {
    render::RenderedFrame f;
    if (k == 0) {
      f.image = still.image;
    } else {
      render::RenderSettings turned = paint.view.settings;
      turned.camera.azimuthDeg = azimuths[k];
      f = paint(turned);
      ms += f.milliseconds;
    }
    const std::string name = frameName(static_cast<int>(k));
    io::writePng(f.image, folder / name);
    movie.add(f.image);
    if (keep) keep->push_back(f.image);
    files.push_back(c.name + "/" + name);
  }
  movie.finish();
  nlohmann::json r = {{"mode", config::toString(c.orbit.mode)},
                      {"frames", azimuths.size()},
                      {"azimuths_deg", azimuths},
                      {"folder", c.name},
                      {"files", files},
                      {"movie", movieName},
                      {"movie_codec", "mp4v (MPEG-4 Part 2), OpenCV VideoWriter"},
                      {"movie_size", {movie.width(), movie.height()}},
                      {"fps", c.orbit.fps},
                      {"ms_all_frames", ms}};
  if (c.orbit.mode == OrbitMode::Rock) r["range_deg"] = c.orbit.rangeDeg;
  return r;
}

struct Output {
  std::string file;
  Image image;
  nlohmann::json record;
  std::vector<std::string> dicomFiles;  // with --dicom: the view's objects, in staging
};

// Everything is written into the staging folder before anything moves into place: a failure
// (a full disk) leaves no partial output. The moves are renames within one file system, in the
// order a reader meets them: each view's PNG and DICOM objects, the orbits' frame folders (an
// earlier run's frames replaced whole) and movies, render.json last, so a reader that waits for
// render.json finds the rest in place. Everything else in the output folder stays.
void writeOutputs(const fs::path& outDir, const std::vector<Output>& outputs,
                  const std::vector<std::string>& orbits, nlohmann::json report,
                  io::StagedFolder& staging) {
  const fs::path& staged = staging.path();
  try {
    for (const auto& out : outputs) {
      io::writePng(out.image, staged / out.file);
      report["views"].push_back(out.record);
    }
    io::writeTextAtomically(staged / "render.json", report.dump(2) + "\n");
  } catch (const Error& e) {
    throw InputError(outDir,
                     std::string("cannot write the renders (is the disk full?): ") + e.what());
  }
  std::vector<std::string> names;
  for (const auto& out : outputs) {
    names.push_back(out.file);
    names.insert(names.end(), out.dicomFiles.begin(), out.dicomFiles.end());
  }
  for (const std::string& name : orbits) {
    names.push_back(name);
    names.push_back(name + ".mp4");
  }
  names.push_back("render.json");
  staging.commit(names);
}

// With --dicom: a view's still as a Secondary Capture and its orbit as one multi-frame SC, in
// a new series of the anatomical source's study (one series per view), written into staging.
std::vector<std::string> writeViewDicom(const study::PlannedView& v, const Image& still,
                                        const std::vector<Image>& orbit, double fps,
                                        const dicomout::DicomIdentity& id, int seriesNumber,
                                        io::StagedFolder& staging) {
  const config::ViewConfig& c = v.config;
  dicomout::SeriesInfo series;
  series.seriesInstanceUid = dicomout::newUid();
  series.seriesNumber = seriesNumber;
  series.description =
      "mvw " + c.name + " (" + toString(c.mode) + ", " + config::toString(c.view) + ")";
  dicomout::CaptureInfo info;
  info.burnedInAnnotation = c.annotate;
  info.derivation = "mvw render: " + std::string(toString(c.mode)) + " of the " +
                    config::toString(c.view) + " view";
  std::vector<std::string> names{c.name + ".dcm"};
  dicomout::writeSecondaryCapture(staging.path() / names.back(), {still}, id, series, info);
  if (!orbit.empty()) {
    info.instanceNumber = 2;
    info.frameTimeMs = 1000.0 / fps;
    info.derivation += ", orbit of " + std::to_string(orbit.size()) + " frames";
    names.push_back(c.name + "-orbit.dcm");
    dicomout::writeSecondaryCapture(staging.path() / names.back(), orbit, id, series, info);
  }
  return names;
}

// Keeps only the views named (--only-view), in the config's order; a name the config lacks is
// the user's error, answered with the names it has.
void keepViews(config::StudyConfig& study, const std::vector<std::string>& names,
               const fs::path& file) {
  if (names.empty()) return;
  std::string known;
  for (const config::ViewConfig& v : study.render.views)
    known += (known.empty() ? "" : ", ") + v.name;
  for (const std::string& name : names) {
    bool found = false;
    for (const config::ViewConfig& v : study.render.views) found = found || v.name == name;
    if (!found)
      throw InputError(file, "--only-view " + name +
                                 ": the config has no view of that name (its views: " + known +
                                 ")");
  }
  std::vector<config::ViewConfig> kept;
  for (config::ViewConfig& v : study.render.views)
    for (const std::string& name : names)
      if (v.name == name) {
        kept.push_back(std::move(v));
        break;
      }
  study.render.views = std::move(kept);
}

}  // namespace

render::RenderedFrame ViewPainter::operator()(const render::RenderSettings& settings) const {
  render::RenderedFrame f = renderer.render(settings);
  if (!view.config.annotate) return f;
  const Volume* functional = session.functional();
  ViewAnnotations a;
  a.caption = caption;
  if (functional)
    a.glyphLegend =
        study::glyphLegend(view, functional->metadata().unit, renderer.functionalRange());
  a.colourBar =
      colourBarOf(settings, session.anatomical(), functional, renderer.functionalRange(), shown);
  a.segmentLegend = segmentLegendOf(settings, session.segments());
  drawAnnotations(f.image, f.camera, settings, a, renderer);
  return f;
}

ViewPainter viewPainter(render::VolumeRenderer& renderer, const study::Session& session,
                        const study::PlannedView& view) {
  const auto [lo, hi] = renderer.valueRange();
  const WindowLevel shown = windowOrFullRange(view.settings.window, lo, hi);
  return ViewPainter{renderer,
                     session,
                     view,
                     shown,
                     study::viewCaption(view, shown),
                     render::showsFunctional(view.settings, session.functional() != nullptr)};
}

RenderedStudy renderStudy(const RenderRequest& request, std::ostream& out, std::ostream& log) {
  config::StudyConfig studyConfig = config::loadStudyConfig(request.study);
  keepViews(studyConfig, request.onlyViews, request.study);
  checkOutputFolder(request.outDir);
  study::Session session(std::move(studyConfig), request.overrides);
  // The context before the volumes: a --gl this machine cannot give fails in milliseconds.
  auto context = makeHeadlessContext(request.gl);
  session.load(request.pacs);
  // Before any render: a source without a DICOM identity needs one from the command line.
  std::optional<dicomout::DicomIdentity> identity;
  if (request.dicom) identity = dicomout::identityOf(session.anatomical(), request.given);
  render::VolumeRenderer renderer(*context, session.anatomical(),
                                  render::parseGradientSource(request.gradient));
  session.attach(renderer);
  std::vector<Output> outputs;
  // Made at the first file, beside the output folder: a run that fails before it writes touches
  // nothing (checkOutputFolder has made sure the nearest folder that exists is writable).
  io::StagedFolder staging(request.outDir, {.purpose = "render", .createNow = false});
  std::vector<std::string> orbits;  // views whose frames and movie wait in staging
  int dicomObjects = 0;
  for (const study::PlannedView& v : session.views(renderer)) {
    const ViewPainter paint = viewPainter(renderer, session, v);
    render::RenderedFrame frame = paint(v.settings);
    nlohmann::json record =
        viewRecord(v, session, renderer, paint.shown, paint.overlayShown, frame, log);
    std::vector<Image> orbitFrames;
    if (v.config.orbit.on()) {
      record["orbit"] = renderOrbit(paint, frame, staging, identity ? &orbitFrames : nullptr);
      orbits.push_back(v.config.name);
    }
    std::vector<std::string> dicomFiles;
    if (identity) {
      dicomFiles = writeViewDicom(v, frame.image, orbitFrames, v.config.orbit.fps, *identity,
                                  1000 + static_cast<int>(outputs.size()) + 1, staging);
      record["dicom"] = dicomFiles;
      dicomObjects += static_cast<int>(dicomFiles.size());
    }
    outputs.push_back({v.config.name + ".png", std::move(frame.image), record, dicomFiles});
    log << "rendered " << v.config.name << " (" << toString(v.config.mode) << ", "
        << config::toString(v.config.view) << ") in " << static_cast<int>(frame.milliseconds)
        << " ms\n";
  }
  writeOutputs(request.outDir, outputs, orbits, studyRecord(session, renderer, *context), staging);
  out << "wrote " << countOf(static_cast<long long>(outputs.size()), "view")
      << " and render.json to " << request.outDir.string() << "\n";
  RenderedStudy rendered;
  rendered.views = static_cast<int>(outputs.size());
  if (identity) {
    out << "wrote " << countOf(dicomObjects, "DICOM Secondary Capture object") << " "
        << dicomout::identityNote(*identity) << "\n";
    // Only once every view is rendered and every object written: exactly this run's objects.
    for (const Output& o : outputs)
      for (const std::string& name : o.dicomFiles)
        rendered.dicomFiles.push_back(request.outDir / name);
  }
  return rendered;
}

}  // namespace mvw::output
