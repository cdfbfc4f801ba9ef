#include "mvw/study/StudyLoader.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>

#include "mvw/core/Check.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/Frame.h"

namespace mvw::study {

Volume readSource(const config::VolumeSource& source, io::ReadOptions options) {
  options.series = source.series;
  options.sliceSpacing = source.sliceSpacingMm;
  Volume volume = io::readVolume(source.path, options);
  // A 4D volume becomes the one 3D volume every view and the registration use, with a note;
  // a frame the volume does not have is bad input, said before any heavy work.
  if (volume.components() > 1 || (source.frame && !source.frame->mean && source.frame->index > 0)) {
    try {
      volume = selectFrame(volume, source.frame.value_or(FrameChoice{}));
    } catch (const InputError& e) {
      throw InputError(e.file(), e.problem() + " (the study config's \"frame\")");
    }
  }
  return volume;
}

Volume readAnatomical(const config::VolumeSource& source, io::ReadOptions options) {
  Volume anatomy = readSource(source, options);
  VolumeMetadata& m = anatomy.metadata();
  if (m.modality.empty() && m.unit.empty()) {
    const auto [lo, hi] = anatomy.valueRange();
    if (lo >= -3100.0 && lo <= -900.0 && hi > 0.0) {
      m.unit = "HU";
      m.notes.push_back("no modality or unit is stated; its values reach down to " +
                        shortNumber(lo) +
                        ", air in Hounsfield units: read as a CT in HU (CT preset, isosurface "
                        "and window)");
    }
  }
  return anatomy;
}

Volume readFunctional(const config::StudyConfig& config, io::ReadOptions options) {
  MVW_CHECK(config.functional.has_value());
  Volume functional = readSource(*config.functional, options);
  // Labels are whole numbers: a PET or a probability map given as "labels" would be read as
  // thousands of one-voxel labels, its glyph classes meaningless.
  if (config.functionalKind == config::FunctionalKind::Labels)
    dispatchScalar(functional.scalarType(), [&](auto zero) {
      using T = decltype(zero);
      if constexpr (std::is_floating_point_v<T>) {
        const T* p = functional.dataAs<T>();
        for (std::size_t i = 0; i < functional.voxelCount() * functional.components(); ++i)
          if (!std::isnan(p[i]) && p[i] != std::floor(p[i])) {
            throw InputError(config.functional->path,
                             "its kind is \"labels\", but it holds the value " +
                                 shortNumber(static_cast<double>(p[i])) +
                                 ": labels are whole numbers (is its kind \"pet\", "
                                 "\"perfusion\" or \"fmri\"?)");
          }
      }
      return 0;
    });
  return functional;
}

Study loadStudy(const config::StudyConfig& config, const io::ReadOptions& options) {
  Study s;
  s.name = config.name;
  s.anatomical = readAnatomical(config.anatomical, options);
  if (config.functional) s.functional = readFunctional(config, options);
  return s;
}

}  // namespace mvw::study
