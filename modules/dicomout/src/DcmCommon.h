#pragma once
// What every object mvw writes shares, in DCMTK terms (private to this library): the patient,
// study and equipment modules from an identity, SOP common, the date and time of creation,
// and the one way a dataset reaches disk (a temporary name, renamed).
#include <filesystem>
#include <string>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>

#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/dicomout/SecondaryCapture.h"

namespace mvw::dicomout::detail {

// DCMTK logs to stderr by default ("Element PixelData encountered, skipping rest of dataset"
// for every header read up to the pixels): only its fatal messages pass. Errors reach mvw as
// OFCondition and are reported by mvw. Once per process; every entry point calls it.
void quietDcmtk();

// Throws mvw::Error with `what` and DCMTK's reason when `c` is not good.
void check(const OFCondition& c, const std::string& what);

// The value of `tag` in `item` as text (all values, backslash-separated); empty when absent.
std::string text(DcmItem& item, const DcmTagKey& tag);

void putString(DcmItem& item, const DcmTagKey& tag, const std::string& value);

// Patient, General Study, Patient Study (where the source gives weight and size), General
// Series (modality, new series UID, number, description), General Equipment, SOP Common
// (class, new instance UID, creation date and time, character set). Returns the SOP instance
// UID.
std::string putCommon(DcmDataset& ds, const DicomIdentity& id, const SeriesInfo& series,
                      const std::string& sopClassUid, const std::string& modality);

// YYYYMMDD and HHMMSS of now (one instant per process, so one render's objects agree).
std::string today();
std::string nowTime();

// A derived value string (DS) of at most 16 characters for `v`.
std::string decimalString(double v);

// Writes the dataset as a DICOM file (explicit VR little endian, meta header from the
// dataset) to a temporary name beside `file` and renames it.
void save(DcmFileFormat& ff, const std::filesystem::path& file);

}  // namespace mvw::dicomout::detail
