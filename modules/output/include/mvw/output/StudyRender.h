#pragma once
// A study config to a folder of views: what `mvw render STUDY -o OUT_DIR` does, and what `mvw
// validate`'s render processes and `mvw batch`'s render studies run (through `mvw render`).
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "mvw/core/WindowLevel.h"
#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Session.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::output {

struct RenderRequest {
  std::filesystem::path study;   // the study config (.json)
  std::filesystem::path outDir;  // made if missing
  study::ViewOverrides overrides;
  std::vector<std::string> onlyViews;  // render only these views, by name (empty: every view)
  std::string gl;                 // --gl (empty: MVW_GL, else auto): output::makeHeadlessContext
  std::string gradient = "auto";  // render::parseGradientSource
  // Also each view's still as a DICOM Secondary Capture and its orbit as one multi-frame SC,
  // in a new series of the anatomical source's study; `given` for a source without a DICOM
  // identity (dicomout::identityOf).
  bool dicom = false;
  dicomout::GivenIdentity given;
  // How the study's PACS series are retrieved into the verified cache (the command line's
  // --cache, --connect-timeout and --read-timeout): study::Session::load.
  pacs::Options pacs;
};

struct RenderedStudy {
  int views = 0;
  std::vector<std::filesystem::path> dicomFiles;  // in outDir, with dicom
};

// Renders every view of the study (with its orbit frames and movie) and writes into outDir,
// once every view has rendered: <view>.png, render.json and, with dicom, the DICOM objects.
// Nothing is written into outDir when anything fails (a staging folder beside it holds the
// files until then). Bad input (the config, a volume, the output folder, --gl) throws
// InputError before any render where it can be known then. Says each view rendered and each
// note on `log`, what it wrote on `out`.
RenderedStudy renderStudy(const RenderRequest& request, std::ostream& out, std::ostream& log);

// A planned view's image as `mvw render` writes it: the render and, where the view annotates,
// its annotations (ViewAnnotations.h). renderStudy paints its stills and orbit frames with it,
// mvw.Study.render (modules/python) its images.
struct ViewPainter {
  render::VolumeRenderer& renderer;
  const study::Session& session;
  const study::PlannedView& view;
  WindowLevel shown;    // the window the view shows (its own, else the full range)
  std::string caption;  // study::viewCaption
  bool overlayShown;    // it shows the functional volume
  render::RenderedFrame operator()(const render::RenderSettings& settings) const;
};
// The painter of `view`, the session attached to `renderer` (study::Session::attach).
ViewPainter viewPainter(render::VolumeRenderer& renderer, const study::Session& session,
                        const study::PlannedView& view);

}  // namespace mvw::output
