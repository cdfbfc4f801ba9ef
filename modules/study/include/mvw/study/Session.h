#pragma once
// A study from its config to a renderer set up to show it, assembled in one place for every
// command that shows a study (`mvw render`, `mvw view`, `mvw bench features`), so that the
// viewer shows what `mvw render` renders by construction, not by copies kept in step. The steps:
//   1. plan the config's views (a view the renderer cannot honour is InputError before any
//      volume is read)                                                       Session()
//   2. read both volumes (readAnatomical, readFunctional)                     load()
//   3. check the views against the anatomy (step, crop box, plane offset)     load()
//   4. place the functional volume (the study's "registration")               load()
//   5. read the segmentation                                                  load()
//   6. give a renderer the functional volume and the segmentation, each where
//      it lies on the anatomy                                                 attach()
//   7. give every view its defaults from the volumes: the modality's preset,
//      the attribute window, the glyph scale                                  views()
#include <optional>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Study.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/FunctionalPlacement.h"
#include "mvw/study/SegmentOverlay.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {

class Session {
 public:
  // Step 1. Throws InputError naming the study file for a view the renderer cannot honour.
  explicit Session(config::StudyConfig study, const ViewOverrides& overrides = {});

  // Steps 2-5. Bad volumes, segmentations and transform files throw InputError naming them.
  // A source on a PACS is read from the verified cache, retrieved first with `pacs` (the
  // caller's cache folder, time-outs and calling AE title: study::localPath).
  void load(const pacs::Options& pacs, const io::ReadOptions& options = {});

  const config::StudyConfig& config() const { return study_; }
  // After load():
  const Volume& anatomical() const;
  const Volume* functional() const;              // null: the study names none
  const FunctionalPlacement* placement() const;  // null without a functional volume
  const SegmentOverlay* segments() const;        // null: the study names no segmentation
  glm::dmat4 anatomicalFromFunctional() const;   // identity without a functional volume

  // Step 6 (the renderer's context current, as every renderer call needs). The viewer moves
  // the functional volume after a registration it runs itself: `anatomicalFromFunctional`
  // then replaces the study's placement, and the segmentation follows it where it shares the
  // functional volume's frame of reference.
  void attach(render::VolumeRenderer& renderer,
              const std::optional<glm::dmat4>& anatomicalFromFunctional = std::nullopt) const;

  // Step 7: the planned views, each with its defaults. functionalRange: the functional
  // volume's value range as the renderer holds it (VolumeRenderer::functionalRange).
  std::vector<PlannedView> views(std::pair<double, double> functionalRange) const;
  std::vector<PlannedView> views(const render::VolumeRenderer& renderer) const {
    return views(renderer.functionalRange());
  }
  // Step 7 for other views over the same volumes (mvw.Study.render: a view given as a dict, a
  // size): `views` in place of the config's, planned with `overrides` as the constructor plans
  // the config's, then given their defaults. Throws InputError as steps 1 and 3 do.
  std::vector<PlannedView> views(std::vector<config::ViewConfig> views,
                                 const ViewOverrides& overrides,
                                 std::pair<double, double> functionalRange) const;

 private:
  config::StudyConfig study_;
  std::vector<PlannedView> planned_;
  std::optional<Study> volumes_;
  std::optional<FunctionalPlacement> placement_;
  std::optional<SegmentOverlay> segments_;
};

// Steps 3 and 7 for views planned from a study whose volumes are at hand: every command's
// views get their defaults here (the viewer's state, which has no renderer, calls it directly).
void prepareViews(std::vector<PlannedView>& views, const config::StudyConfig& study,
                  const Volume& anatomical, const Volume* functional,
                  std::pair<double, double> functionalRange);

}  // namespace mvw::study
