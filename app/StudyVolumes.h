#pragma once
// Reading a study's volumes: each source with its own DICOM series choice.
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

namespace mvw::app {

// The volume a study names, read with `options` and the source's own series selection.
Volume readSource(const config::VolumeSource& source, io::ReadOptions options = {});

}  // namespace mvw::app
