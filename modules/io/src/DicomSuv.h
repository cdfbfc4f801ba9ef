#pragma once
// PET values in SUVbw from the series' radiopharmaceutical, weight and time tags
// (core/Suv.h does the arithmetic) (internal to mvw_io: vtk-dicom types stay inside this
// folder).
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

class vtkDICOMMetaData;

namespace mvw::io::detail {

// A PT series' unit: its Units as stored unless BQML; Bq/ml converted to SUVbw (float32, the
// factor in metadata().suvFactor) when options.suv and the tags allow, with a note saying
// which and why.
void fillPetUnitAndSuv(Volume& volume, vtkDICOMMetaData* meta, const ReadOptions& options);

}  // namespace mvw::io::detail
