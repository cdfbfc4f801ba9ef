#include "StudyVolumes.h"

namespace mvw::app {

Volume readSource(const config::VolumeSource& source, io::ReadOptions options) {
  options.series = source.series;
  return io::readVolume(source.path, options);
}

}  // namespace mvw::app
