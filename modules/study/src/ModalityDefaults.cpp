#include "mvw/study/ModalityDefaults.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "mvw/render/TransferFunction.h"

namespace mvw::study {

namespace {

bool isCt(const Volume& v) { return v.metadata().modality == "CT" || v.metadata().unit == "HU"; }

bool inSuv(const Volume& v) { return v.metadata().unit.rfind("SUV", 0) == 0; }

// Hounsfield values every CT reader knows: cortical bone starts near 300 HU; the soft-tissue
// window is W 400 L 40.
constexpr double kCtBoneIsoHu = 300.0;
constexpr WindowLevel kCtSoftTissue{400.0, 40.0};
// Without a unit to go by, the isosurface sits at this fraction of the value range.
constexpr double kIsoFractionOfRange = 0.4;

}  // namespace

bool isEmission(const Volume& volume) {
  const std::string& m = volume.metadata().modality;
  return m == "PT" || m == "NM";
}

std::string defaultPreset(const Volume& anatomy) {
  if (isCt(anatomy)) return "ct-bone";
  if (isEmission(anatomy)) return "pet-hot-metal";
  return "mr-default";
}

std::string noSuvNote(const Volume& volume) {
  if (!isEmission(volume) || inSuv(volume)) return "";
  const std::string& unit = volume.metadata().unit;
  for (const std::string& note : volume.metadata().notes) {
    if (note.find("SUV") == std::string::npos) continue;
    // "values in Bq/ml: SUVbw not computed (PatientWeight missing or not positive)": the
    // reason in the parentheses, the unit being said beside every value already.
    const std::size_t open = note.find(" not computed (");
    if (open != std::string::npos && note.back() == ')')
      return "no SUV: " + note.substr(open + 15, note.size() - open - 16);
    return "no SUV: " + note;
  }
  return "no SUV: values in " + (unit.empty() ? std::string("no unit") : unit);
}

ModalityDefaults modalityDefaults(const Volume& anatomy, std::pair<double, double> valueRange) {
  const auto [lo, hi] = valueRange;
  ModalityDefaults d;
  d.preset = defaultPreset(anatomy);
  if (isCt(anatomy)) {
    d.iso = kCtBoneIsoHu;
    d.mpr = kCtSoftTissue;
  } else {
    d.iso = lo + kIsoFractionOfRange * (hi - lo);
    if (inSuv(anatomy) && hi > kSuvLesionThreshold && lo < kSuvLesionThreshold)
      d.iso = kSuvLesionThreshold;
    d.mpr = windowOrFullRange(WindowLevel{}, lo, hi);
  }
  if (isEmission(anatomy)) {
    const auto [low, high] = defaultFunctionalDisplayWindow(anatomy, valueRange);
    d.mpr = WindowLevel{high - low, 0.5 * (low + high)};
    d.mode3d = RenderMode::Mip;
    d.mipColors = ColorMap::GreyInverted;
  }
  return d;
}

std::vector<std::string> presetsFor(const Volume& anatomy) {
  std::vector<std::string> out;
  for (const std::string& name : render::transferPresetNames())
    if (isCt(anatomy) || render::transferPreset(name).relative) out.push_back(name);
  return out;
}

ValueWindow defaultAttributeWindow(config::FunctionalKind kind, const Volume& functional,
                                   std::pair<double, double> range) {
  // fMRI statistic maps (z or t, from the NIfTI intent code): from the usual cluster-forming
  // threshold, z = 2.3.
  const std::string& unit = functional.metadata().unit;
  if (kind != config::FunctionalKind::Labels && (unit == "z" || unit == "t")) {
    if (!(range.second > kStatisticThreshold)) return {};
    return {kStatisticThreshold, range.second};
  }
  const bool emission =
      kind == config::FunctionalKind::Pet || kind == config::FunctionalKind::Spect ||
      functional.metadata().modality == "PT" || functional.metadata().modality == "NM";
  if (!emission || kind == config::FunctionalKind::Labels) return {};
  const double max = range.second;
  if (inSuv(functional)) return {kSuvLesionThreshold, std::max(max, kSuvLesionThreshold + 1.0)};
  if (!(max > 0)) return {};
  return {kRelativeUptakeThreshold * max, max};
}

ValueWindow defaultFunctionalDisplayWindow(const Volume& functional,
                                           std::pair<double, double> range) {
  const auto [lo, hi] = range;
  const glm::ivec3 d = functional.dimensions();
  // At most about a million voxels, evenly strided: a percentile needs no more.
  const std::size_t total = static_cast<std::size_t>(d.x) * d.y * d.z;
  const std::size_t stride = std::max<std::size_t>(1, total / 1000000);
  std::vector<double> above;  // the voxels above the background
  for (std::size_t n = 0; n < total; n += stride) {
    const int i = static_cast<int>(n % d.x), j = static_cast<int>(n / d.x % d.y),
              k = static_cast<int>(n / (static_cast<std::size_t>(d.x) * d.y));
    const double v = functional.value(i, j, k);
    if (std::isfinite(v) && v > lo) above.push_back(v);
  }
  if (above.empty() || !(hi > lo)) return {lo, hi > lo ? hi : lo + 1.0};
  std::sort(above.begin(), above.end());
  const auto percentile = [&](double p) {
    return above[static_cast<std::size_t>(p * static_cast<double>(above.size() - 1))];
  };
  const double top = percentile(0.995);
  if (inSuv(functional)) return {0.0, top > 5.0 ? 10.0 : 5.0};
  // Below 0 is noise in perfusion (an ASL subtraction) and most other maps: from 0; a
  // statistic map's negative values (deactivation) are data.
  const std::string& unit = functional.metadata().unit;
  const double bottom = lo < 0.0 && (unit == "z" || unit == "t") ? percentile(0.01) : 0.0;
  if (!(top > bottom)) return {lo, hi};
  return {bottom, top};
}

}  // namespace mvw::study
