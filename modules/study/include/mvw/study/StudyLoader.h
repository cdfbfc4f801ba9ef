#pragma once
// Reading a study's volumes into a core Study: each source with its own DICOM series choice.
// `mvw render`, `mvw view`, `mvw info`, `mvw bench` and `mvw validate` all read through here.
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Study.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

namespace mvw::study {

// The volume a study names, read with `options` and the source's own series selection.
Volume readSource(const config::VolumeSource& source, io::ReadOptions options = {});

// Both volumes of the study (the functional one when the config names it).
Study loadStudy(const config::StudyConfig& config, const io::ReadOptions& options = {});

}  // namespace mvw::study
