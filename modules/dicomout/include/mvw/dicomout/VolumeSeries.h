#pragma once
// A volume as a DICOM image series, one file per slice, on the volume's own grid: the values
// of a resampled functional volume on the anatomical grid and Frame of Reference. The series
// keeps its source's modality and image modules (PET stays PET: units, radiopharmaceutical,
// decay and the other SUV tags; MR and CT their acquisition attributes); values as 16-bit
// integers with a rescale slope per slice.
#include <filesystem>

#include "mvw/core/Volume.h"
#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/dicomout/SecondaryCapture.h"

namespace mvw::dicomout {

// source: the identity of the volume the values came from (DICOM: its header is the
// template); frame: whose Frame of Reference the grid lies in. The files are written into a
// new folder `folder` (staged beside it and moved in whole). Returns the number of files.
// PET in SUVbw is written in Bq/ml (Units BQML) by the volume's SUV factor, so a reader
// computes the same SUV from the same tags. Throws InputError for a source that is not a
// DICOM PT, MR or CT series.
int writeVolumeSeries(const std::filesystem::path& folder, const Volume& values,
                      const DicomIdentity& source, const DicomIdentity& frame,
                      const SeriesInfo& series, const std::string& derivation);

}  // namespace mvw::dicomout
