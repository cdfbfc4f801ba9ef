#include "DcmCommon.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <mutex>

#include <dcmtk/oflog/oflog.h>

#include "mvw/core/Error.h"
#include "mvw/core/Version.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::dicomout::detail {

namespace {

std::tm creationTime() {
  static const std::time_t t = std::time(nullptr);
  std::tm tm{};
  localtime_r(&t, &tm);
  return tm;
}

}  // namespace

void quietDcmtk() {
  static std::once_flag once;
  std::call_once(once, [] { OFLog::configure(OFLogger::FATAL_LOG_LEVEL); });
}

void check(const OFCondition& c, const std::string& what) {
  if (c.bad()) throw Error(what + ": " + c.text());
}

void putString(DcmItem& item, const DcmTagKey& tag, const std::string& value) {
  check(item.putAndInsertString(tag, value.c_str()),
        "DICOM " + std::string(DcmTag(tag).getTagName()));
}

std::string today() {
  const std::tm tm = creationTime();
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y%m%d", &tm);
  return buf;
}

std::string nowTime() {
  const std::tm tm = creationTime();
  char buf[16];
  std::strftime(buf, sizeof buf, "%H%M%S", &tm);
  return buf;
}

std::string decimalString(double v) {
  char buf[32];
  for (int digits = 10; digits > 1; --digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strlen(buf) <= 16) return buf;
  }
  return "0";
}

std::string putCommon(DcmDataset& ds, const DicomIdentity& id, const SeriesInfo& series,
                      const std::string& sopClassUid, const std::string& modality) {
  quietDcmtk();
  if (!id.characterSet.empty()) putString(ds, DCM_SpecificCharacterSet, id.characterSet);
  const std::string sopInstanceUid = newUid();
  putString(ds, DCM_SOPClassUID, sopClassUid);
  putString(ds, DCM_SOPInstanceUID, sopInstanceUid);
  putString(ds, DCM_InstanceCreationDate, today());
  putString(ds, DCM_InstanceCreationTime, nowTime());
  // Patient
  putString(ds, DCM_PatientName, id.patientName);
  putString(ds, DCM_PatientID, id.patientId);
  putString(ds, DCM_PatientBirthDate, id.patientBirthDate);
  putString(ds, DCM_PatientSex, id.patientSex);
  // General Study
  putString(ds, DCM_StudyInstanceUID, id.studyInstanceUid);
  putString(ds, DCM_StudyDate, id.studyDate);
  putString(ds, DCM_StudyTime, id.studyTime);
  putString(ds, DCM_ReferringPhysicianName, id.referringPhysician);
  putString(ds, DCM_StudyID, id.studyId);
  putString(ds, DCM_AccessionNumber, id.accessionNumber);
  if (!id.studyDescription.empty()) putString(ds, DCM_StudyDescription, id.studyDescription);
  // General Series
  putString(ds, DCM_Modality, modality);
  putString(ds, DCM_SeriesInstanceUID,
            series.seriesInstanceUid.empty() ? newUid() : series.seriesInstanceUid);
  putString(ds, DCM_SeriesNumber, std::to_string(series.seriesNumber));
  putString(ds, DCM_Laterality, "");  // 2C: a render or registration of no one side
  putString(ds, DCM_SeriesDate, today());
  putString(ds, DCM_SeriesTime, nowTime());
  if (!series.description.empty())
    putString(ds, DCM_SeriesDescription, series.description.substr(0, 64));
  // General Equipment
  putString(ds, DCM_Manufacturer, "mvw");
  putString(ds, DCM_ManufacturerModelName, "mvw");
  putString(ds, DCM_SoftwareVersions, kVersion);
  return sopInstanceUid;
}

void save(DcmFileFormat& ff, const std::filesystem::path& file) {
  io::writeAtomically(file, [&](const std::filesystem::path& tmp) {
    const OFCondition c = ff.saveFile(tmp.c_str(), EXS_LittleEndianExplicit, EET_ExplicitLength,
                                      EGL_recalcGL, EPD_noChange, 0, 0, EWM_createNewMeta);
    if (c.bad()) throw Error(tmp.string() + ": cannot write the DICOM file: " + c.text());
  });
}

std::string text(DcmItem& item, const DcmTagKey& tag) {
  OFString s;
  if (item.findAndGetOFStringArray(tag, s).good()) return s.c_str();
  return {};
}

}  // namespace mvw::dicomout::detail
