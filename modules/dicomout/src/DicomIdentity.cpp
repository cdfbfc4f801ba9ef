#include "mvw/dicomout/DicomIdentity.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>

#include "DcmCommon.h"
#include "mvw/core/Error.h"

namespace mvw::dicomout {

namespace fs = std::filesystem;
using detail::text;

namespace {

std::string& uidRoot() {
  static std::string root;
  return root;
}

// 128 bits as a decimal number (no leading zeros), by repeated division of four 32-bit limbs.
std::string decimal(std::array<std::uint32_t, 4> limbs) {
  std::string digits;
  auto zero = [&] { return std::all_of(limbs.begin(), limbs.end(), [](auto l) { return !l; }); };
  while (!zero()) {
    std::uint64_t rest = 0;
    for (auto& l : limbs) {
      const std::uint64_t cur = (rest << 32) | l;
      l = static_cast<std::uint32_t>(cur / 10);
      rest = cur % 10;
    }
    digits.push_back(static_cast<char>('0' + rest));
  }
  if (digits.empty()) digits.assign(1, '0');
  std::reverse(digits.begin(), digits.end());
  return digits;
}

}  // namespace

std::string newUid(const std::string& root) {
  static std::random_device device;
  static std::mt19937_64 engine(
      (static_cast<std::uint64_t>(device()) << 32) ^ device() ^
      static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
  std::array<std::uint32_t, 4> limbs{};
  for (auto& l : limbs) l = static_cast<std::uint32_t>(engine());
  // RFC 4122 version 4 (random), variant 10.
  limbs[1] = (limbs[1] & 0xffff0fffu) | 0x00004000u;
  limbs[2] = (limbs[2] & 0x3fffffffu) | 0x80000000u;
  const std::string r = root.empty() ? uidRoot() : root;
  if (r.empty()) return "2.25." + decimal(limbs);
  std::string uid = r + "." + decimal(limbs);
  if (uid.size() > 64) uid.resize(64);
  if (uid.back() == '.') uid.pop_back();
  return uid;
}

void setUidRoot(const std::string& root) { uidRoot() = root; }

void checkUidRoot(const std::string& root, const std::string& what) {
  auto bad = [&](const std::string& why) {
    throw InputError(what, "the UID root '" + root + "' " + why);
  };
  if (root.empty()) return;
  if (root.size() > 40) bad("is longer than 40 characters (a UID holds 64, the rest is random)");
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = root.find('.', start);
    const std::string part = root.substr(start, dot == std::string::npos ? dot : dot - start);
    if (part.empty() ||
        !std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; }))
      bad("is not digits separated by dots");
    if (part.size() > 1 && part[0] == '0') bad("has a component with a leading zero");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
}

DicomIdentity identityOf(const Volume& volume, const GivenIdentity& given) {
  detail::quietDcmtk();
  const VolumeMetadata& md = volume.metadata();
  DicomIdentity id;
  if (md.format == "DICOM" && !md.seriesInstanceUid.empty()) {
    std::vector<fs::path> files;
    std::error_code ec;
    const fs::path source(md.sourcePath);
    if (fs::is_directory(source, ec)) {
      for (auto it = fs::recursive_directory_iterator(
               source, fs::directory_options::skip_permission_denied, ec);
           it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (ec) break;
        if (it.depth() > 8) it.disable_recursion_pending();
        if (it->is_regular_file(ec)) files.push_back(it->path());
      }
      std::sort(files.begin(), files.end());
    } else {
      files.push_back(source);
    }
    for (const fs::path& f : files) {
      DcmFileFormat ff;
      if (ff.loadFileUntilTag(f.c_str(), EXS_Unknown, EGL_noChange, 4096, ERM_autoDetect,
                              DCM_PixelData)
              .bad())
        continue;
      DcmDataset& ds = *ff.getDataset();
      if (text(ds, DCM_SeriesInstanceUID) != md.seriesInstanceUid) continue;
      if (!id.fromDicom) {
        id.fromDicom = true;
        id.firstFile = f;
        id.characterSet = text(ds, DCM_SpecificCharacterSet);
        id.patientId = text(ds, DCM_PatientID);
        id.patientName = text(ds, DCM_PatientName);
        id.patientBirthDate = text(ds, DCM_PatientBirthDate);
        id.patientSex = text(ds, DCM_PatientSex);
        id.studyInstanceUid = text(ds, DCM_StudyInstanceUID);
        id.studyDate = text(ds, DCM_StudyDate);
        id.studyTime = text(ds, DCM_StudyTime);
        id.studyId = text(ds, DCM_StudyID);
        id.accessionNumber = text(ds, DCM_AccessionNumber);
        id.referringPhysician = text(ds, DCM_ReferringPhysicianName);
        id.studyDescription = text(ds, DCM_StudyDescription);
        id.seriesInstanceUid = md.seriesInstanceUid;
        id.modality = text(ds, DCM_Modality);
        id.frameOfReferenceUid = text(ds, DCM_FrameOfReferenceUID);
      }
      SourceImage image;
      image.sopClassUid = text(ds, DCM_SOPClassUID);
      image.sopInstanceUid = text(ds, DCM_SOPInstanceUID);
      Float64 p[3];
      image.hasPosition = true;
      for (int a = 0; a < 3; ++a)
        if (ds.findAndGetFloat64(DCM_ImagePositionPatient, p[a], a).bad())
          image.hasPosition = false;
      if (image.hasPosition) image.position = {p[0], p[1], p[2]};
      if (!image.sopInstanceUid.empty()) id.images.push_back(image);
    }
  }
  const std::string name = md.sourcePath.empty() ? std::string("the volume") : md.sourcePath;
  if (!given.patientId.empty()) id.patientId = given.patientId;
  if (!given.patientName.empty()) id.patientName = given.patientName;
  if (id.patientId.empty())
    throw InputError(name, id.fromDicom
                               ? "its DICOM headers give no Patient ID: give --patient-id "
                                 "(and --patient-name) for the DICOM objects"
                               : "is not DICOM, so it has no patient or study to write DICOM "
                                 "objects into: give --patient-id and --patient-name (a new "
                                 "study UID is made)");
  if (!id.fromDicom) {
    if (given.patientName.empty())
      throw InputError(name, "is not DICOM: give --patient-name as well as --patient-id");
    id.studyInstanceUid = newUid();
    id.frameOfReferenceUid = md.frameOfReferenceUid.empty() ? newUid() : md.frameOfReferenceUid;
    id.studyDate = "";
    id.modality = md.modality;
  }
  if (id.studyInstanceUid.empty()) id.studyInstanceUid = newUid();
  if (id.frameOfReferenceUid.empty()) id.frameOfReferenceUid = newUid();
  return id;
}

std::string identityNote(const DicomIdentity& id) {
  if (id.fromDicom)
    return "in the study " + id.studyInstanceUid + " of patient " + id.patientId +
           " (from the DICOM source)";
  return "in a NEW study " + id.studyInstanceUid + " for patient " + id.patientId + " (" +
         id.patientName + "): the source is not DICOM";
}

}  // namespace mvw::dicomout
