#include "mvw/dicomout/SegmentationWriter.h"

#include <memory>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmiod/iodreferences.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <glm/geometric.hpp>

#include "DcmCommon.h"
#include "mvw/core/Check.h"
#include "mvw/core/Error.h"
#include "mvw/core/Version.h"

namespace mvw::dicomout {

using namespace detail;

namespace {

std::string ds(double v) { return decimalString(v); }

// The source image at `position` (within 0.01 mm), or null: a grid resampled from uneven
// slices has planes that no image lies on.
const SourceImage* imageAt(const DicomIdentity& source, const glm::dvec3& position) {
  for (const SourceImage& image : source.images)
    if (image.hasPosition && glm::length(image.position - position) < 0.01) return &image;
  return nullptr;
}

// Patient, study, series and frame of reference of the source; a new SOP Instance UID.
void setIdentity(DcmSegmentation& seg, const DicomIdentity& source, const SeriesInfo& series) {
  check(seg.getPatient().setPatientName(source.patientName.c_str(), OFFalse), "PatientName");
  check(seg.getPatient().setPatientID(source.patientId.c_str(), OFFalse), "PatientID");
  check(seg.getPatient().setPatientBirthDate(source.patientBirthDate.c_str(), OFFalse),
        "PatientBirthDate");
  check(seg.getPatient().setPatientSex(source.patientSex.c_str(), OFFalse), "PatientSex");
  IODGeneralStudyModule& study = seg.getStudy();
  check(study.setStudyInstanceUID(source.studyInstanceUid.c_str(), OFFalse), "StudyInstanceUID");
  check(study.setStudyDate(source.studyDate.c_str(), OFFalse), "StudyDate");
  check(study.setStudyTime(source.studyTime.c_str(), OFFalse), "StudyTime");
  check(study.setStudyID(source.studyId.c_str(), OFFalse), "StudyID");
  check(study.setAccessionNumber(source.accessionNumber.c_str(), OFFalse), "AccessionNumber");
  check(study.setReferringPhysicianName(source.referringPhysician.c_str(), OFFalse),
        "ReferringPhysicianName");
  if (!source.studyDescription.empty())
    check(study.setStudyDescription(source.studyDescription.c_str(), OFFalse), "StudyDescription");
  check(seg.getSeries().setSeriesInstanceUID(
            (series.seriesInstanceUid.empty() ? newUid() : series.seriesInstanceUid).c_str()),
        "SeriesInstanceUID");
  check(seg.getSeries().setSeriesNumber(std::to_string(series.seriesNumber).c_str()),
        "SeriesNumber");
  if (!series.description.empty())
    check(seg.getSeries().setSeriesDescription(series.description.substr(0, 64).c_str(), OFFalse),
          "SeriesDescription");
  check(seg.getSeries().setSeriesDate(today().c_str()), "SeriesDate");
  check(seg.getSeries().setSeriesTime(nowTime().c_str()), "SeriesTime");
  check(seg.getFrameOfReference().setFrameOfReferenceUID(source.frameOfReferenceUid.c_str()),
        "FrameOfReferenceUID");
  check(seg.getSOPCommon().setSOPInstanceUID(newUid().c_str()), "SOPInstanceUID");
  if (!source.characterSet.empty())
    check(seg.getSOPCommon().setSpecificCharacterSet(source.characterSet.c_str(), OFFalse),
          "SpecificCharacterSet");
}

// The grid: rows along j, columns along i, one frame per k; the frames indexed by segment and
// position.
void setGrid(DcmSegmentation& seg, const Volume& grid, const std::filesystem::path& file) {
  const glm::dvec3 spacing = grid.spacing();
  const glm::dmat3 dir = grid.direction();
  FGPixelMeasures measures;
  check(measures.setPixelSpacing((ds(spacing.y) + "\\" + ds(spacing.x)).c_str()), "PixelSpacing");
  check(measures.setSliceThickness(ds(spacing.z).c_str()), "SliceThickness");
  check(measures.setSpacingBetweenSlices(ds(spacing.z).c_str()), "SpacingBetweenSlices");
  check(seg.addForAllFrames(measures), "Pixel Measures");
  std::unique_ptr<FGPlaneOrientationPatient> orientation(FGPlaneOrientationPatient::createMinimal(
      ds(dir[0].x).c_str(), ds(dir[0].y).c_str(), ds(dir[0].z).c_str(), ds(dir[1].x).c_str(),
      ds(dir[1].y).c_str(), ds(dir[1].z).c_str()));
  if (!orientation) throw Error(file.string() + ": cannot make the plane orientation");
  check(seg.addForAllFrames(*orientation), "Plane Orientation");
  const std::string dimensionUid = newUid();
  IODMultiframeDimensionModule& dimensions = seg.getDimensions();
  check(dimensions.addDimensionIndex(DCM_ReferencedSegmentNumber, dimensionUid.c_str(),
                                     DCM_SegmentIdentificationSequence, "ReferencedSegmentNumber"),
        "Dimension Index");
  check(dimensions.addDimensionIndex(DCM_ImagePositionPatient, dimensionUid.c_str(),
                                     DCM_PlanePositionSequence, "ImagePositionPatient"),
        "Dimension Index");
}

// One segment: its label and description, and a frame for each slice of the grid that holds a
// voxel of it (the SEG IOD lets a segment leave out empty frames: a 153-voxel lesion of a
// 299-slice PET is a few frames, not 299), each with its position and the source image it lies
// on; its bits appended to `packed` from `bit` on (returned advanced).
std::size_t addSegment(DcmSegmentation& seg, const SegmentMask& mask, const Volume& grid,
                       const DicomIdentity& source, const std::string& algorithm,
                       std::vector<Uint8>& packed, std::size_t bit) {
  const glm::ivec3 dims = grid.dimensions();
  const std::size_t slice = static_cast<std::size_t>(dims.x) * dims.y;
  std::vector<Uint8> frame(slice);
  DcmSegment* segment = nullptr;
  // The segmented property type (SCT), and the label of a segment that has none of its own: what
  // its code says it is.
  const char* typeCode = mask.metabolic ? "108369006" : "52988006";
  const char* typeMeaning = mask.metabolic ? "Neoplasm" : "Lesion";
  const std::string label = mask.label.empty() ? typeMeaning : mask.label;
  check(
      DcmSegment::create(segment, label.substr(0, 64).c_str(),
                         CodeSequenceMacro("49755003", "SCT", "Morphologically Altered Structure"),
                         CodeSequenceMacro(typeCode, "SCT", typeMeaning),
                         DcmSegTypes::SAT_SEMIAUTOMATIC, algorithm.substr(0, 64).c_str()),
      "Segment");
  if (!mask.description.empty())
    check(segment->setSegmentDescription(mask.description.substr(0, 64).c_str(), OFFalse),
          "SegmentDescription");
  Uint16 number = 0;
  check(seg.addSegment(segment, number), "Segment");
  // Voxels by slice (the list is ascending: slices in order).
  std::vector<std::vector<std::size_t>> bySlice(static_cast<std::size_t>(dims.z));
  for (std::size_t v : mask.voxels) bySlice[v / slice].push_back(v % slice);
  for (int k = 0; k < dims.z; ++k) {
    const auto& voxels = bySlice[static_cast<std::size_t>(k)];
    if (voxels.empty()) continue;
    std::fill(frame.begin(), frame.end(), Uint8{0});
    packed.resize((bit + slice + 7) / 8, Uint8{0});
    for (std::size_t p : voxels) {
      frame[p] = 1;
      packed[(bit + p) / 8] |= static_cast<Uint8>(1u << ((bit + p) % 8));
    }
    bit += slice;
    const glm::dvec3 position = grid.worldFromIndexPoint({0.0, 0.0, double(k)});
    std::unique_ptr<FGPlanePosPatient> pos(FGPlanePosPatient::createMinimal(
        ds(position.x).c_str(), ds(position.y).c_str(), ds(position.z).c_str()));
    FGFrameContent frameContent;
    check(frameContent.setDimensionIndexValues(number, 0), "Dimension Index Values");
    check(frameContent.setDimensionIndexValues(static_cast<Uint32>(k + 1), 1),
          "Dimension Index Values");
    OFVector<FGBase*> perFrame;
    perFrame.push_back(pos.get());
    perFrame.push_back(&frameContent);
    std::unique_ptr<FGDerivationImage> derivation;
    if (const SourceImage* image = imageAt(source, position)) {
      ImageSOPInstanceReferenceMacro ref;
      check(ref.setReferencedSOPClassUID(image->sopClassUid.c_str()), "ReferencedSOPClassUID");
      check(ref.setReferencedSOPInstanceUID(image->sopInstanceUid.c_str()),
            "ReferencedSOPInstanceUID");
      OFVector<ImageSOPInstanceReferenceMacro> refs;
      refs.push_back(ref);
      derivation.reset(DcmSegmentation::createDerivationImageFG(refs, ""));
      if (derivation) perFrame.push_back(derivation.get());
    }
    check(seg.addFrame(frame.data(), number, perFrame), "SEG frame");
  }
  return bit;
}

// The source images the segmentation was drawn on (Common Instance Reference).
void addSourceReferences(DcmSegmentation& seg, const DicomIdentity& source) {
  if (!source.fromDicom) return;
  IODReferences references;
  for (const SourceImage& image : source.images)
    references.add(new IODImageReference(source.patientId.c_str(), source.studyInstanceUid.c_str(),
                                         source.seriesInstanceUid.c_str(),
                                         image.sopInstanceUid.c_str(), image.sopClassUid.c_str()));
  seg.getCommonInstanceReference().addReferences(references, source.studyInstanceUid.c_str());
}

}  // namespace

void writeSegmentation(const std::filesystem::path& file, const Volume& grid,
                       const std::vector<SegmentMask>& segments, const DicomIdentity& source,
                       const SeriesInfo& series, const std::string& algorithm) {
  quietDcmtk();
  const glm::ivec3 dims = grid.dimensions();
  bool any = false;
  for (const SegmentMask& s : segments) any = any || !s.voxels.empty();
  if (!any) throw InputError(file, "the segmentation holds no voxel: no SEG written");

  const IODGeneralEquipmentModule::EquipmentInfo equipment("mvw", "mvw", "1", kVersion);
  const ContentIdentificationMacro content("1", "MVW_SEGMENTATION",
                                           series.description.substr(0, 64), "");
  DcmSegmentation* raw = nullptr;
  check(DcmSegmentation::createBinarySegmentation(raw, static_cast<Uint16>(dims.y),
                                                  static_cast<Uint16>(dims.x), equipment, content),
        "DICOM SEG");
  std::unique_ptr<DcmSegmentation> seg(raw);

  setIdentity(*seg, source, series);
  setGrid(*seg, grid, file);

  // The frames' bits as the standard packs them: one stream, frame after frame, with no padding
  // between frames (PS3.5 8.1.1). DCMTK 3.6.7 pads each frame to a whole byte and cuts the
  // total, which shifts every frame after the first by a bit per frame when rows x columns is
  // not a multiple of 8 (DicomOut.SegReadBackVoxelForVoxel, 23 x 17 frames: 792 voxels wrong),
  // so the pixel data is written again from this stream below.
  std::vector<Uint8> packed;
  std::size_t bit = 0;
  for (const SegmentMask& mask : segments)
    bit = addSegment(*seg, mask, grid, source, algorithm, packed, bit);
  addSourceReferences(*seg, source);

  DcmFileFormat ff;
  DcmDataset& dataset = *ff.getDataset();
  check(seg->writeDataset(dataset), file.string() + ": DICOM SEG");
  MVW_CHECK_EQ(bit % (static_cast<std::size_t>(dims.x) * dims.y), std::size_t{0});
  MVW_CHECK_EQ(packed.size(), (bit + 7) / 8);
  check(dataset.putAndInsertUint8Array(DCM_PixelData, packed.data(),
                                       static_cast<unsigned long>(packed.size())),
        "PixelData");
  save(ff, file);
}

}  // namespace mvw::dicomout
