#pragma once
// What a view shows before the reader chooses: the transfer preset, isosurface value and MPR
// window that suit the anatomy's modality. The one home of the rule `mvw render` (views
// without a preset) and `mvw view` (its panes when the study says nothing) share.
#include <string>
#include <utility>
#include <vector>

#include "mvw/config/StudyConfig.h"

#include "mvw/core/ColorMap.h"
#include "mvw/core/RenderMode.h"
#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"

namespace mvw::study {

struct ModalityDefaults {
  std::string preset;  // transfer function preset name
  double iso = 0.0;    // isosurface value in the volume's unit
  WindowLevel mpr;     // the MPR panes' window (and an emission image's MIP's)
  // The view a study gets where its config names none (config::ViewConfig::implied): the
  // viewer's 3D pane and `mvw render`'s one view. A composite with the preset; a PET or SPECT
  // read alone: its MIP in `mipColors` under the `mpr` window, as nuclear medicine reads it.
  RenderMode mode3d = RenderMode::Composite;
  ColorMap mipColors = ColorMap::Grey;
};

// Whether the volume is an emission image: PET or SPECT (DICOM modality PT or NM).
bool isEmission(const Volume& volume);

// CT (or HU): bone preset, bone isosurface (300 HU), soft-tissue window (W 400 L 40).
// PET/SPECT: hot-metal preset, in SUV the isosurface at SUV 2.5 (kSuvLesionThreshold) where the
// volume reaches it, a grey-inverted MIP as the implied view, and as window the one the volume
// gets where it is shown alone (defaultFunctionalDisplayWindow: 0-5 or 0-10 SUV; without SUV 0
// to the 99.5th percentile), so that a PET opened from a folder or the PACS is not washed out
// by its few hottest voxels. Otherwise (MR, unknown): the MR preset, the isosurface at 40 % of
// the value range and the full range as window.
ModalityDefaults modalityDefaults(const Volume& anatomy, std::pair<double, double> valueRange);

// Why an emission image's values are not SUV, for every pane and readout that shows it:
// "no SUV: PatientWeight missing or not positive" (the reader's note, io's DicomSuv, without
// its "values in Bq/ml" preamble); "" for a volume in SUV and for other modalities.
std::string noSuvNote(const Volume& volume);

// The preset part of modalityDefaults, which needs no value range.
std::string defaultPreset(const Volume& anatomy);

// The transfer presets that can show this volume: the Hounsfield ones (ct-*, absolute values)
// for CT only; the relative ones (over the value range) for every volume. The viewer's P key and
// preset list offer these, so no CT preset blanks a PET in SUV.
std::vector<std::string> presetsFor(const Volume& anatomy);

// What a functional reader starts from, the one home of these numbers.
inline constexpr double kSuvLesionThreshold = 2.5;        // SUVbw: the usual lesion threshold
inline constexpr double kRelativeUptakeThreshold = 0.41;  // of the maximum (metabolic volumes)
inline constexpr double kStatisticThreshold = 2.3;  // z (or t): the usual cluster-forming threshold

// The attribute window (colour map, glyph beta) of a view whose config names none:
//   PET or SPECT in SUV: from SUV 2.5 to the maximum (at least 1 SUV wide, so a study with no
//     uptake above 2.5 shows none);
//   PET or SPECT in other units (Bq/ml, counts, none): from 41 % of the maximum to the maximum;
//   a statistic map (unit z or t: the NIfTI intent code) that is not a label map: from 2.3 to
//     the maximum (none when nothing exceeds 2.3);
//   otherwise (fMRI signal, perfusion, dose, labels, other): none (unset), the full value range.
// range: the functional volume's value range (min, max).
ValueWindow defaultAttributeWindow(config::FunctionalKind kind, const Volume& functional,
                                   std::pair<double, double> range);

// The functional volume's window where it is shown alone (the viewer's PET/CT functional pane
// and rotating MIP) and the study names none: PET or SPECT in SUV from 0 to 5, or to 10 where
// more than 0.5 % of the voxels above the background exceed 5; otherwise from 0 (a statistic
// map, unit z or t, with values below 0: from the 1st percentile) to the 99.5th percentile of
// the voxels above the
// background (the minimum), so that a few hot voxels do not set the scale. The full range where
// that leaves nothing. range: the functional volume's value range (min, max).
ValueWindow defaultFunctionalDisplayWindow(const Volume& functional,
                                           std::pair<double, double> range);

}  // namespace mvw::study
