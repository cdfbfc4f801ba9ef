#include "mvw/study/StudyLoader.h"

#include "mvw/core/Error.h"
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

Study loadStudy(const config::StudyConfig& config, const io::ReadOptions& options) {
  Study s;
  s.name = config.name;
  s.anatomical = readSource(config.anatomical, options);
  if (config.functional) s.functional = readSource(*config.functional, options);
  return s;
}

}  // namespace mvw::study
