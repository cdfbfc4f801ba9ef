#include "mvw/study/StudyLoader.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>

#include "mvw/config/ServerList.h"
#include "mvw/core/Check.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/Frame.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::study {

std::filesystem::path localPath(const config::VolumeSource& source, const pacs::Options& pacs) {
  if (source.pacs.empty()) return source.path;
  return pacs::cachedSeries(config::resolveServer(source.pacs), source.study, source.series, pacs);
}

void rethrowQuarantined(const config::VolumeSource& source, const std::filesystem::path& folder,
                        const InputError& e, const pacs::Options& pacs) {
  if (source.pacs.empty()) return;
  // A file of the series, not the folder as a whole (a series mvw does not read as a volume
  // reads no better when retrieved again).
  const std::filesystem::path rel =
      e.file().lexically_normal().lexically_relative(folder.lexically_normal());
  if (rel.empty() || rel == "." || *rel.begin() == "..") return;
  std::filesystem::path moved;
  try {
    moved = pacs::quarantineSeries(folder, e.what(), pacs);
  } catch (const std::exception&) {
    return;  // the read's own error says more than why the move failed
  }
  throw InputError(moved / rel, e.problem() + " (a PACS series in the cache that failed to read: " +
                                    "moved into the cache's quarantine, retrieved again on the " +
                                    "next run; `mvw pacs cache --clear-quarantine` empties it)");
}

Volume readSource(const config::VolumeSource& source, io::ReadOptions options,
                  const pacs::Options& pacs) {
  // A PACS series is read from its verified cache folder, which holds that series alone.
  options.series = source.pacs.empty() ? source.series : std::string();
  options.sliceSpacing = source.sliceSpacingMm;
  Volume volume = readLocal(source, pacs, [&](const std::filesystem::path& path) {
    return io::readVolume(path, options);
  });
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

namespace {

// Whether a tenth or more of the voxels (component 0, NaN skipped) lie where a CT in HU has
// them in quantity and an MR does not: air (-1050 .. -950 HU, where -1000 and the -1024 floor
// fall) and the scanners' padding values outside the reconstruction circle (-2048, -2000,
// -3024), all whole numbers. A field map, a phase or velocity image or a difference image
// reaches below -900 too, but spreads its values instead of piling a tenth of the volume at
// air. Stops as soon as a tenth of all voxels is air (a CT's first slices usually get there):
// this runs while a study opens.
bool tenthAtAir(const Volume& v) {
  return dispatchScalar(v.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* p = v.dataAs<T>();
    const std::size_t n = v.voxelCount(), stride = static_cast<std::size_t>(v.components());
    std::size_t air = 0, counted = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = static_cast<double>(p[i * stride]);
      if (std::isnan(x)) continue;
      ++counted;
      if (x != std::floor(x)) continue;
      if ((x >= -1050.0 && x <= -950.0) || x == -2048.0 || x == -2000.0 || x == -3024.0)
        if (10 * ++air >= n) return true;  // a tenth of every voxel, so of the counted ones
    }
    return counted > 0 && 10 * air >= counted;
  });
}

}  // namespace

Volume readAnatomical(const config::VolumeSource& source, io::ReadOptions options,
                      const pacs::Options& pacs) {
  Volume anatomy = readSource(source, options, pacs);
  VolumeMetadata& m = anatomy.metadata();
  if (m.modality.empty() && m.unit.empty()) {
    const auto [lo, hi] = anatomy.valueRange();
    if (lo >= -3100.0 && lo <= -900.0 && hi > 0.0 && tenthAtAir(anatomy)) {
      m.unit = "HU";
      m.notes.push_back("no modality or unit is stated; its values reach down to " +
                        shortNumber(lo) +
                        " and a tenth or more of its voxels lie at air in Hounsfield units "
                        "(-1000, or a scanner's padding): read as a CT in HU (CT preset, "
                        "isosurface and window)");
    }
  }
  return anatomy;
}

Volume readFunctional(const config::StudyConfig& config, io::ReadOptions options,
                      const pacs::Options& pacs) {
  MVW_CHECK(config.functional.has_value());
  Volume functional = readSource(*config.functional, options, pacs);
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

Study loadStudy(const config::StudyConfig& config, const io::ReadOptions& options,
                const pacs::Options& pacs) {
  Study s;
  s.name = config.name;
  s.anatomical = readAnatomical(config.anatomical, options, pacs);
  if (config.functional) s.functional = readFunctional(config, options, pacs);
  return s;
}

bool isStudyConfig(const std::filesystem::path& path) { return path.extension() == ".json"; }

}  // namespace mvw::study
