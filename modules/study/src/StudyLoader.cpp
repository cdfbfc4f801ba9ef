#include "mvw/study/StudyLoader.h"

namespace mvw::study {

Volume readSource(const config::VolumeSource& source, io::ReadOptions options) {
  options.series = source.series;
  options.sliceSpacing = source.sliceSpacingMm;
  return io::readVolume(source.path, options);
}

Study loadStudy(const config::StudyConfig& config, const io::ReadOptions& options) {
  Study s;
  s.name = config.name;
  s.anatomical = readSource(config.anatomical, options);
  if (config.functional) s.functional = readSource(*config.functional, options);
  return s;
}

}  // namespace mvw::study
