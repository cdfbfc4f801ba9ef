#include "mvw/dicomout/SpatialRegistration.h"

#include <map>

#include "DcmCommon.h"

namespace mvw::dicomout {

using namespace detail;

namespace {

// FrameOfReferenceTransformationMatrix: 16 values, row by row (DICOM PS3.3 C.20.2.1.1).
std::string matrixString(const glm::dmat4& m) {
  std::string s;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      if (!s.empty()) s += '\\';
      s += decimalString(m[c][r]);
    }
  return s;
}

// One item of the Registration Sequence: the source frame of reference (and its series' images,
// which the Common Instance Reference module then lists) onto the registered one.
void putRegistration(DcmDataset& ds, const DicomIdentity& source, const glm::dmat4& m,
                     const std::string& type, const std::string& comment) {
  DcmItem* reg = nullptr;
  check(ds.findOrCreateSequenceItem(DCM_RegistrationSequence, reg, -2), "Registration Sequence");
  putString(*reg, DCM_FrameOfReferenceUID, source.frameOfReferenceUid);
  for (const SourceImage& image : source.images) {
    DcmItem* ref = nullptr;
    check(reg->findOrCreateSequenceItem(DCM_ReferencedImageSequence, ref, -2),
          "Referenced Image Sequence");
    putString(*ref, DCM_ReferencedSOPClassUID, image.sopClassUid);
    putString(*ref, DCM_ReferencedSOPInstanceUID, image.sopInstanceUid);
  }
  DcmItem* matrixReg = nullptr;
  check(reg->findOrCreateSequenceItem(DCM_MatrixRegistrationSequence, matrixReg, -2),
        "Matrix Registration Sequence");
  if (!comment.empty())
    putString(*matrixReg, DCM_FrameOfReferenceTransformationComment, comment.substr(0, 64));
  check(matrixReg->insertEmptyElement(DCM_RegistrationTypeCodeSequence), "Registration Type Code");
  DcmItem* matrix = nullptr;
  check(matrixReg->findOrCreateSequenceItem(DCM_MatrixSequence, matrix, -2), "Matrix Sequence");
  putString(*matrix, DCM_FrameOfReferenceTransformationMatrix, matrixString(m));
  putString(*matrix, DCM_FrameOfReferenceTransformationMatrixType, type);
}

}  // namespace

void writeSpatialRegistration(const std::filesystem::path& file, const DicomIdentity& fixed,
                              const DicomIdentity& moving, const glm::dmat4& fixedFromMoving,
                              bool affine, const SeriesInfo& series, const std::string& comment) {
  DcmFileFormat ff;
  DcmDataset& ds = *ff.getDataset();
  putCommon(ds, fixed, series, UID_SpatialRegistrationStorage, "REG");
  // Frame of Reference: the registered coordinate system is the fixed volume's.
  putString(ds, DCM_FrameOfReferenceUID, fixed.frameOfReferenceUid);
  putString(ds, DCM_PositionReferenceIndicator, "");
  // Spatial Registration (with the Content Identification macro).
  putString(ds, DCM_InstanceNumber, "1");
  putString(ds, DCM_ContentLabel, "MVW_REGISTRATION");
  putString(
      ds, DCM_ContentDescription,
      affine ? "rigid then affine, Mattes mutual information" : "rigid, Mattes mutual information");
  putString(ds, DCM_ContentCreatorName, "");
  putString(ds, DCM_ContentDate, today());
  putString(ds, DCM_ContentTime, nowTime());
  if (fixed.frameOfReferenceUid != moving.frameOfReferenceUid)
    putRegistration(ds, fixed, glm::dmat4(1.0), "RIGID", "");
  putRegistration(ds, moving, fixedFromMoving, affine ? "AFFINE" : "RIGID", comment);
  // Common Instance Reference: both series, by study.
  std::map<std::string, std::vector<const DicomIdentity*>> byStudy;
  for (const DicomIdentity* id : {&fixed, &moving})
    if (id->fromDicom && !id->images.empty() &&
        (id == &fixed || moving.seriesInstanceUid != fixed.seriesInstanceUid))
      byStudy[id->studyInstanceUid].push_back(id);
  for (const auto& [study, ids] : byStudy) {
    DcmItem* studyItem = &ds;
    if (study != fixed.studyInstanceUid) {
      check(ds.findOrCreateSequenceItem(DCM_StudiesContainingOtherReferencedInstancesSequence,
                                        studyItem, -2),
            "Studies Containing Other Referenced Instances Sequence");
      putString(*studyItem, DCM_StudyInstanceUID, study);
    }
    for (const DicomIdentity* id : ids) {
      DcmItem* seriesItem = nullptr;
      check(studyItem->findOrCreateSequenceItem(DCM_ReferencedSeriesSequence, seriesItem, -2),
            "Referenced Series Sequence");
      putString(*seriesItem, DCM_SeriesInstanceUID, id->seriesInstanceUid);
      for (const SourceImage& image : id->images) {
        DcmItem* instance = nullptr;
        check(seriesItem->findOrCreateSequenceItem(DCM_ReferencedInstanceSequence, instance, -2),
              "Referenced Instance Sequence");
        putString(*instance, DCM_ReferencedSOPClassUID, image.sopClassUid);
        putString(*instance, DCM_ReferencedSOPInstanceUID, image.sopInstanceUid);
      }
    }
  }
  save(ff, file);
}

}  // namespace mvw::dicomout
