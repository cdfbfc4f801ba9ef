#include "mvw/study/ModalityDefaults.h"

namespace mvw::study {

namespace {

bool isCt(const Volume& v) { return v.metadata().modality == "CT" || v.metadata().unit == "HU"; }

// Hounsfield values every CT reader knows: cortical bone starts near 300 HU; the soft-tissue
// window is W 400 L 40.
constexpr double kCtBoneIsoHu = 300.0;
constexpr WindowLevel kCtSoftTissue{400.0, 40.0};
// Without a unit to go by, the isosurface sits at this fraction of the value range.
constexpr double kIsoFractionOfRange = 0.4;

}  // namespace

std::string defaultPreset(const Volume& anatomy) {
  if (isCt(anatomy)) return "ct-bone";
  const std::string& m = anatomy.metadata().modality;
  if (m == "PT" || m == "NM") return "pet-hot-metal";
  return "mr-default";
}

ModalityDefaults modalityDefaults(const Volume& anatomy, std::pair<double, double> valueRange) {
  const auto [lo, hi] = valueRange;
  ModalityDefaults d;
  d.preset = defaultPreset(anatomy);
  if (isCt(anatomy)) {
    d.isoValue = kCtBoneIsoHu;
    d.mpr = kCtSoftTissue;
  } else {
    d.isoValue = lo + kIsoFractionOfRange * (hi - lo);
    d.mpr = windowOrFullRange(0.0, 0.0, lo, hi);
  }
  return d;
}

}  // namespace mvw::study
