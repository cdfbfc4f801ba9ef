#include "mvw/study/Session.h"

#include <algorithm>
#include <optional>

#include "mvw/core/Check.h"
#include "mvw/study/ModalityDefaults.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::study {

namespace {

// The window the viewer's MPR panes start from (ViewerState): the first MPR view's own, else
// the modality's. Only where a view shows the anatomy on a cut face without a window of its own
// (the value range is a pass over the voxels).
std::optional<WindowLevel> studyMprWindow(const std::vector<PlannedView>& views,
                                          const Volume& anatomical) {
  if (std::none_of(views.begin(), views.end(), [](const PlannedView& v) {
        return !v.config.window.set() && render::showsAnatomyOnCutFace(v.settings);
      }))
    return std::nullopt;
  for (const PlannedView& v : views)
    if (v.settings.mode == render::RenderMode::Mpr) {
      if (v.settings.window.set()) return v.settings.window;
      break;
    }
  return modalityDefaults(anatomical, anatomical.valueRange()).mpr;
}

}  // namespace

Session::Session(config::StudyConfig study, const ViewOverrides& overrides)
    : study_(std::move(study)), planned_(planViews(study_, overrides)) {}

void Session::load(const pacs::Options& pacs, const io::ReadOptions& options) {
  volumes_ = loadStudy(study_, options, pacs);
  // Before the placement: a registration can take minutes, a bad crop box is known now.
  checkViewsAgainstAnatomy(planned_, volumes_->anatomical, study_.file);
  if (volumes_->functional)
    placement_ = placeFunctional(study_, volumes_->anatomical, *volumes_->functional);
  if (study_.segmentation) segments_ = readSegmentOverlay(*study_.segmentation, options, pacs);
}

const Volume& Session::anatomical() const {
  MVW_CHECK(volumes_.has_value());
  return volumes_->anatomical;
}

const Volume* Session::functional() const {
  MVW_CHECK(volumes_.has_value());
  return volumes_->functional ? &*volumes_->functional : nullptr;
}

const FunctionalPlacement* Session::placement() const {
  return placement_ ? &*placement_ : nullptr;
}

const SegmentOverlay* Session::segments() const { return segments_ ? &*segments_ : nullptr; }

glm::dmat4 Session::anatomicalFromFunctional() const {
  return placement_ ? placement_->anatomicalFromFunctional : glm::dmat4(1.0);
}

void Session::attach(render::VolumeRenderer& renderer,
                     const std::optional<glm::dmat4>& anatomicalFromFunctional) const {
  const glm::dmat4 placed = anatomicalFromFunctional.value_or(this->anatomicalFromFunctional());
  if (const Volume* f = functional()) renderer.setFunctional(*f, placed);
  if (segments_)
    renderer.setSegmentation(segments_->masks, segments_->colours,
                             anatomicalFromSegmentation(*segments_, functional(), placed));
}

std::vector<PlannedView> Session::views(std::pair<double, double> functionalRange) const {
  std::vector<PlannedView> views = planned_;
  prepareViews(views, study_, anatomical(), functional(), functionalRange);
  return views;
}

std::vector<PlannedView> Session::views(std::vector<config::ViewConfig> views,
                                        const ViewOverrides& overrides,
                                        std::pair<double, double> functionalRange) const {
  config::StudyConfig study = study_;
  study.render.views = std::move(views);
  std::vector<PlannedView> planned = planViews(study, overrides);
  prepareViews(planned, study, anatomical(), functional(), functionalRange);
  return planned;
}

void prepareViews(std::vector<PlannedView>& views, const config::StudyConfig& study,
                  const Volume& anatomical, const Volume* functional,
                  std::pair<double, double> functionalRange) {
  checkViewsAgainstAnatomy(views, anatomical, study.file);
  // A PET or SPECT read alone: its window from its values (a pass over them), once.
  std::optional<ModalityDefaults> emission;
  if (isEmission(anatomical)) emission = modalityDefaults(anatomical, anatomical.valueRange());
  for (PlannedView& v : views)
    if (emission) applyModalityView(v, anatomical, *emission);
  const std::optional<WindowLevel> mpr = studyMprWindow(views, anatomical);
  for (PlannedView& v : views) {
    applyDefaultPreset(v, anatomical);
    if (mpr) applyCutFaceWindow(v, *mpr);
    if (functional) {
      applyAttributeDefaults(v, study.functionalKind, *functional, functionalRange);
      applyGlyphScale(v, anatomical, *functional);
    }
  }
}

}  // namespace mvw::study
