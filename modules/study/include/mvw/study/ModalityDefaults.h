#pragma once
// What a view shows before the reader chooses: the transfer preset, isosurface value and MPR
// window that suit the anatomy's modality. The one home of the rule `mvw render` (views
// without a preset) and `mvw view` (its panes when the study says nothing) share.
#include <string>
#include <utility>

#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"

namespace mvw::study {

struct ModalityDefaults {
  std::string preset;     // transfer function preset name
  double isoValue = 0.0;  // isosurface value in the volume's unit
  WindowLevel mpr;        // the MPR panes' window
};

// CT (or HU): bone preset, bone isosurface (300 HU), soft-tissue window (W 400 L 40).
// PET/SPECT: hot-metal preset. Otherwise (MR, unknown): the MR preset, the isosurface at 40 %
// of the value range and the full range as window.
ModalityDefaults modalityDefaults(const Volume& anatomy, std::pair<double, double> valueRange);

// The preset part of modalityDefaults, which needs no value range.
std::string defaultPreset(const Volume& anatomy);

}  // namespace mvw::study
