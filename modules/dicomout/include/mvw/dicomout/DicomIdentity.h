#pragma once
// Who and what a DICOM object mvw writes belongs to: the patient and study of the volume it
// was made from, that volume's series, frame of reference and images (to reference them).
// Read from the headers of the source series' files; a volume that is not DICOM (NIfTI,
// MetaImage) has none, and a patient ID and name must be given for it (a new study UID).
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"

namespace mvw::dicomout {

struct SourceImage {
  std::string sopClassUid;
  std::string sopInstanceUid;
  glm::dvec3 position{0.0};  // ImagePositionPatient, LPS mm
  bool hasPosition = false;
};

struct DicomIdentity {
  bool fromDicom = false;    // read from a DICOM series (false: given on the command line)
  std::string characterSet;  // SpecificCharacterSet of the source ("" = default repertoire)
  std::string patientId, patientName, patientBirthDate, patientSex;
  std::string studyInstanceUid, studyDate, studyTime, studyId, accessionNumber, referringPhysician,
      studyDescription;
  // The source series (empty where not DICOM).
  std::string seriesInstanceUid, modality, frameOfReferenceUid;
  std::vector<SourceImage> images;
  std::filesystem::path firstFile;  // one file of the series: the header template
};

// What the user gives for a source without a DICOM identity (or with an empty Patient ID).
struct GivenIdentity {
  std::string patientId;
  std::string patientName;
};

// A new UID: "2.25." and a random UUID (version 4) as a decimal number, or, with a root
// ("1.2.826.0.1.3680043.10.1234"), the root and the UUID's decimal digits cut to 64 characters.
std::string newUid(const std::string& root = "");
// Sets the root newUid() uses when it is given none (from the config or the command line).
void setUidRoot(const std::string& root);
// Throws InputError naming `what` when the root is not a valid UID prefix (digits and dots,
// no leading zero in a component, at most 40 characters to leave room for the UUID).
void checkUidRoot(const std::string& root, const std::string& what);

// The identity of `volume`'s source: its DICOM series' headers where it was read from DICOM
// (patient, study, series, frame of reference, each image's UIDs and position), else empty
// with fromDicom false. `given` overrides the patient ID and name; where the source has no
// Patient ID and none is given, throws InputError naming the source and the options.
// A source that is not DICOM gets a new study UID and frame of reference UID.
DicomIdentity identityOf(const Volume& volume, const GivenIdentity& given = {});

// The words that tell the reader whose study the objects went into ("in the study UID of
// patient ID (from the DICOM source)", or a new study for a source that is not DICOM).
std::string identityNote(const DicomIdentity& id);

}  // namespace mvw::dicomout
