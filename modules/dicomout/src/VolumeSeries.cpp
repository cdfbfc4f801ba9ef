#include "mvw/dicomout/VolumeSeries.h"

#include <algorithm>
#include <cmath>

#include "DcmCommon.h"
#include "mvw/core/Error.h"
#include "mvw/io/StagedFolder.h"

namespace mvw::dicomout {

using namespace detail;

namespace fs = std::filesystem;

namespace {

// What the series keeps of its source, by modality: the modules its IOD needs that describe the
// acquisition (the image's own position, size and values are the new grid's). PET keeps
// everything its SUV is computed from.
const std::vector<DcmTagKey> kPetTags = {DCM_Units,
                                         DCM_CountsSource,
                                         DCM_SeriesType,
                                         DCM_ReprojectionMethod,
                                         DCM_NumberOfRRIntervals,
                                         DCM_NumberOfTimeSlots,
                                         DCM_NumberOfTimeSlices,
                                         DCM_CorrectedImage,
                                         DCM_RandomsCorrectionMethod,
                                         DCM_AttenuationCorrectionMethod,
                                         DCM_ScatterCorrectionMethod,
                                         DCM_DecayCorrection,
                                         DCM_ReconstructionDiameter,
                                         DCM_ConvolutionKernel,
                                         DCM_ReconstructionMethod,
                                         DCM_DetectorLinesOfResponseUsed,
                                         DCM_AxialAcceptance,
                                         DCM_AxialMash,
                                         DCM_TransverseMash,
                                         DCM_CollimatorType,
                                         DCM_RadiopharmaceuticalInformationSequence,
                                         DCM_PatientOrientationCodeSequence,
                                         DCM_PatientGantryRelationshipCodeSequence,
                                         DCM_FrameReferenceTime,
                                         DCM_ActualFrameDuration,
                                         DCM_DecayFactor,
                                         DCM_DoseCalibrationFactor,
                                         DCM_ScatterFractionFactor,
                                         DCM_DeadTimeFactor,
                                         DCM_PrimaryPromptsCountsAccumulated,
                                         DCM_SliceSensitivityFactor,
                                         DCM_AcquisitionStartCondition,
                                         DCM_AcquisitionTerminationCondition,
                                         DCM_EnergyWindowRangeSequence};
const std::vector<DcmTagKey> kMrTags = {
    DCM_ScanningSequence,      DCM_SequenceVariant, DCM_ScanOptions,
    DCM_MRAcquisitionType,     DCM_RepetitionTime,  DCM_EchoTime,
    DCM_EchoTrainLength,       DCM_InversionTime,   DCM_SequenceName,
    DCM_MagneticFieldStrength, DCM_ImagedNucleus,   DCM_ImagingFrequency,
    DCM_NumberOfAverages,      DCM_FlipAngle,       DCM_ReceiveCoilName,
    DCM_TransmitCoilName,      DCM_AngioFlag};
const std::vector<DcmTagKey> kCtTags = {DCM_KVP, DCM_AcquisitionNumber, DCM_ConvolutionKernel,
                                        DCM_XRayTubeCurrent, DCM_ExposureTime};
// Patient Study, General Series and General Image attributes that hold for every slice.
const std::vector<DcmTagKey> kCommonTags = {
    DCM_PatientWeight,   DCM_PatientSize,     DCM_PatientAge,      DCM_BodyPartExamined,
    DCM_PatientPosition, DCM_ProtocolName,    DCM_AcquisitionDate, DCM_AcquisitionTime,
    DCM_Manufacturer,    DCM_InstitutionName, DCM_StationName,     DCM_Laterality};

// Private tags and group lengths (retired), recursively: a source's private sequences and the
// group lengths inside copied sequence items.
void removePrivate(DcmItem& item) {
  for (unsigned long i = item.card(); i-- > 0;) {
    DcmElement* e = item.getElement(i);
    if (e->getTag().isPrivate() || e->getTag().getElement() == 0x0000) {
      delete item.remove(e);
      continue;
    }
    if (e->ident() == EVR_SQ) {
      auto* sq = static_cast<DcmSequenceOfItems*>(e);
      for (unsigned long n = 0; n < sq->card(); ++n) removePrivate(*sq->getItem(n));
    }
  }
}

struct SeriesKind {
  std::string sopClass;
  const std::vector<DcmTagKey>* modalityTags;
};

// The storage class and acquisition tags of the source's modality; InputError for a source
// that is not a DICOM PT, MR or CT series, or a volume of several values a voxel.
SeriesKind kindOf(const Volume& values, const DicomIdentity& source) {
  const std::string& modality = source.modality;
  SeriesKind kind{"", nullptr};
  if (modality == "PT")
    kind = {UID_PositronEmissionTomographyImageStorage, &kPetTags};
  else if (modality == "MR")
    kind = {UID_MRImageStorage, &kMrTags};
  else if (modality == "CT")
    kind = {UID_CTImageStorage, &kCtTags};
  if (!source.fromDicom || !kind.modalityTags)
    throw InputError(values.metadata().sourcePath,
                     source.fromDicom
                         ? "is a DICOM " + modality +
                               " series: only PT, MR and CT are written back as DICOM series"
                         : std::string("is not DICOM: its modality and acquisition header are "
                                       "unknown, so no DICOM series of it is written"));
  if (values.components() != 1)
    throw InputError(
        values.metadata().sourcePath,
        "has " + std::to_string(values.components()) +
            " values a voxel: only single-valued volumes are written as a DICOM series");
  return kind;
}

// DERIVED\SECONDARY (PET: DERIVED\PRIMARY, the only value 2 its IOD allows), then the
// source's own values 3 and on (PET: the image's kind).
std::string imageTypeOf(DcmItem& tmpl, const std::string& modality) {
  std::string imageType = modality == "PT" ? "DERIVED\\PRIMARY" : "DERIVED\\SECONDARY";
  const std::string src = text(tmpl, DCM_ImageType);
  const std::size_t first = src.find('\\');
  const std::size_t second = first == std::string::npos ? first : src.find('\\', first + 1);
  if (second != std::string::npos) imageType += src.substr(second);
  return imageType;
}

// Image Plane: slice k's position, the grid's orientation and spacing.
void putPlane(DcmDataset& ds, const Volume& values, int k) {
  const glm::dvec3 spacing = values.spacing();
  const glm::dmat3 dir = values.direction();
  const glm::dvec3 p = values.worldFromIndexPoint({0.0, 0.0, double(k)});
  putString(ds, DCM_ImagePositionPatient,
            decimalString(p.x) + "\\" + decimalString(p.y) + "\\" + decimalString(p.z));
  std::string iop;
  for (int c = 0; c < 2; ++c)
    for (int a = 0; a < 3; ++a) {
      if (!iop.empty()) iop += '\\';
      iop += decimalString(dir[c][a]);
    }
  putString(ds, DCM_ImageOrientationPatient, iop);
  putString(ds, DCM_PixelSpacing, decimalString(spacing.y) + "\\" + decimalString(spacing.x));
  putString(ds, DCM_SliceThickness, decimalString(spacing.z));
}

// Slice k's values (times toStored): signed 16 bits, a slope per slice (intercept 0, as PET
// requires); NaN as 0. `pixels` is the slice's buffer, reused from slice to slice.
void putPixels(DcmDataset& ds, const Volume& values, int k, double toStored,
               const std::string& modality, std::vector<Sint16>& pixels) {
  const glm::ivec3 dims = values.dimensions();
  double maxAbs = 0.0;
  for (int j = 0; j < dims.y; ++j)
    for (int i = 0; i < dims.x; ++i) {
      const double v = values.value(i, j, k) * toStored;
      if (std::isfinite(v)) maxAbs = std::max(maxAbs, std::abs(v));
    }
  const double slope = maxAbs > 0 ? maxAbs / 32767.0 : 1.0;
  std::size_t o = 0;
  for (int j = 0; j < dims.y; ++j)
    for (int i = 0; i < dims.x; ++i) {
      const double v = values.value(i, j, k) * toStored;
      pixels[o++] = std::isfinite(v) ? static_cast<Sint16>(std::lround(v / slope)) : Sint16{0};
    }
  putString(ds, DCM_RescaleIntercept, "0");
  putString(ds, DCM_RescaleSlope, decimalString(slope));
  if (modality != "PT") putString(ds, DCM_RescaleType, modality == "CT" ? "HU" : "US");
  check(ds.putAndInsertUint16(DCM_SamplesPerPixel, 1), "SamplesPerPixel");
  putString(ds, DCM_PhotometricInterpretation, "MONOCHROME2");
  check(ds.putAndInsertUint16(DCM_Rows, static_cast<Uint16>(dims.y)), "Rows");
  check(ds.putAndInsertUint16(DCM_Columns, static_cast<Uint16>(dims.x)), "Columns");
  check(ds.putAndInsertUint16(DCM_BitsAllocated, 16), "BitsAllocated");
  check(ds.putAndInsertUint16(DCM_BitsStored, 16), "BitsStored");
  check(ds.putAndInsertUint16(DCM_HighBit, 15), "HighBit");
  check(ds.putAndInsertUint16(DCM_PixelRepresentation, 1), "PixelRepresentation");
  check(ds.putAndInsertUint16Array(DCM_PixelData, reinterpret_cast<const Uint16*>(pixels.data()),
                                   static_cast<unsigned long>(pixels.size())),
        "PixelData");
}

}  // namespace

int writeVolumeSeries(const fs::path& folder, const Volume& values, const DicomIdentity& source,
                      const DicomIdentity& frame, const SeriesInfo& series,
                      const std::string& derivation) {
  const std::string modality = source.modality;
  const auto [sopClass, modalityTags] = kindOf(values, source);
  DcmFileFormat templateFile;
  if (templateFile
          .loadFileUntilTag(source.firstFile.c_str(), EXS_Unknown, EGL_noChange, 4096,
                            ERM_autoDetect, DCM_PixelData)
          .bad())
    throw InputError(source.firstFile, "cannot read its DICOM header again");
  DcmDataset& tmpl = *templateFile.getDataset();

  // PET in SUVbw is stored in Bq/ml, the unit its tags describe (a reader computes the same
  // SUV from the same tags).
  const VolumeMetadata& md = values.metadata();
  double toStored = 1.0;
  if (modality == "PT" && md.suvFactor && md.unit.rfind("SUV", 0) == 0)
    toStored = 1.0 / *md.suvFactor;

  const glm::ivec3 dims = values.dimensions();
  const std::string seriesUid =
      series.seriesInstanceUid.empty() ? newUid() : series.seriesInstanceUid;
  SeriesInfo s = series;
  s.seriesInstanceUid = seriesUid;

  // Staged beside the folder and moved in whole, replacing an earlier series.
  io::StagedFolder staging(folder, {.purpose = "series", .mode = io::StagedFolder::Mode::Replace});

  const std::string imageType = imageTypeOf(tmpl, modality);
  std::vector<Sint16> pixels(static_cast<std::size_t>(dims.x) * dims.y);
  for (int k = 0; k < dims.z; ++k) {
    DcmFileFormat ff;
    DcmDataset& ds = *ff.getDataset();
    const std::string sopInstanceUid = putCommon(ds, source, s, sopClass, modality);
    for (const auto* list : {&kCommonTags, modalityTags})
      for (const DcmTagKey& tag : *list) tmpl.findAndInsertCopyOfElement(tag, &ds, OFTrue);
    // Series dates stay the acquisition's (PET decay correction is timed from them).
    for (const DcmTagKey& tag : {DCM_SeriesDate, DCM_SeriesTime})
      tmpl.findAndInsertCopyOfElement(tag, &ds, OFTrue);
    removePrivate(ds);
    // 2C, required for CT and MR without a Patient Orientation Code Sequence: empty where the
    // source does not say.
    if (ds.tagExists(DCM_PatientOrientationCodeSequence))
      delete ds.remove(DCM_PatientPosition);  // not both (PET: the code sequence is the one)
    else if (!ds.tagExists(DCM_PatientPosition))
      putString(ds, DCM_PatientPosition, "");
    putString(ds, DCM_Manufacturer, "mvw");
    // Frame of Reference: the grid's (the anatomical volume's).
    putString(ds, DCM_FrameOfReferenceUID, frame.frameOfReferenceUid);
    putString(ds, DCM_PositionReferenceIndicator, "");
    // General Image, Image Plane.
    putString(ds, DCM_InstanceNumber, std::to_string(k + 1));
    putString(ds, DCM_PatientOrientation, "");
    putString(ds, DCM_ContentDate, today());
    putString(ds, DCM_ContentTime, nowTime());
    putString(ds, DCM_ImageType, imageType);
    putString(ds, DCM_DerivationDescription, derivation.substr(0, 1024));
    putPlane(ds, values, k);
    if (modality == "PT") {
      check(ds.putAndInsertUint16(DCM_ImageIndex, static_cast<Uint16>(k + 1)), "ImageIndex");
      check(ds.putAndInsertUint16(DCM_NumberOfSlices, static_cast<Uint16>(dims.z)),
            "NumberOfSlices");
      putString(ds, DCM_Units, text(tmpl, DCM_Units).empty() ? "BQML" : text(tmpl, DCM_Units));
    }
    putPixels(ds, values, k, toStored, modality, pixels);
    char name[32];
    std::snprintf(name, sizeof name, "IM%05d.dcm", k + 1);
    (void)sopInstanceUid;
    save(ff, staging.path() / name);
  }
  staging.commit();
  return dims.z;
}

}  // namespace mvw::dicomout
