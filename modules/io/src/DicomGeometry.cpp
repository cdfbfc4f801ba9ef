#include "DicomGeometry.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDICOMValue.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMatrix4x4.h>

#include <glm/geometric.hpp>

#include "SiemensMosaic.h"
#include "SliceGeometry.h"
#include "mvw/core/Format.h"

namespace mvw::io::detail {

namespace {

// Each output slice's ImagePositionPatient (vtk-dicom maps output slice -> file and frame);
// empty when any is missing.
std::vector<glm::dvec3> slicePositions(vtkDICOMReader* reader) {
  vtkIntArray* fileIndex = reader->GetFileIndexArray();
  vtkIntArray* frameIndex = reader->GetFrameIndexArray();
  vtkDICOMMetaData* meta = reader->GetMetaData();
  std::vector<glm::dvec3> positions;
  if (!fileIndex || !frameIndex || fileIndex->GetNumberOfTuples() < 2) return positions;
  for (vtkIdType s = 0; s < fileIndex->GetNumberOfTuples(); ++s) {
    const vtkDICOMValue& ipp = meta->Get(fileIndex->GetComponent(s, 0),
                                         frameIndex->GetComponent(s, 0), DC::ImagePositionPatient);
    if (ipp.GetNumberOfValues() != 3) return {};
    const glm::dvec3 p(ipp.GetDouble(0), ipp.GetDouble(1), ipp.GetDouble(2));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return {};
    positions.push_back(p);
  }
  return positions;
}

// Slices without any ImagePositionPatient: stacked in vtk-dicom's order (instance numbers),
// as far apart as SpacingBetweenSlices, else SliceThickness, else 1 mm, with a note; where
// the volume lies in the patient is unknown.
Volume spaceUnplacedSlices(Volume volume, vtkDICOMMetaData* meta) {
  double step = meta->Get(0, DC::SpacingBetweenSlices).AsDouble();
  std::string from = "SpacingBetweenSlices";
  if (!(step > 0.0 && step < 1e3)) {
    step = meta->Get(0, DC::SliceThickness).AsDouble();
    from = "SliceThickness";
  }
  if (!(step > 0.0 && step < 1e3)) {
    step = 1.0;
    from = "neither SpacingBetweenSlices nor SliceThickness says otherwise";
  }
  glm::dmat4 m = volume.worldFromIndex();
  const glm::dvec3 axis(m[2]);
  if (glm::length(axis) > 0.0) m[2] = glm::dvec4(glm::normalize(axis) * step, 0.0);
  volume.setWorldFromIndex(m);
  volume.metadata().notes.push_back(
      "no slice has an ImagePositionPatient: slices stacked in instance order " +
      shortNumber(step) + " mm apart (" + from +
      "); where the volume lies in the patient is unknown");
  return volume;
}

bool isMosaic(vtkDICOMMetaData* meta) {
  const vtkDICOMValue& type = meta->Get(0, DC::ImageType);
  for (unsigned int i = 0; i < type.GetNumberOfValues(); ++i)
    if (type.GetString(i) == "MOSAIC") return true;
  return false;
}

Volume unpackMosaicFrom(Volume volume, vtkDICOMMetaData* meta) {
  const vtkDICOMTag tag =
      meta->ResolvePrivateTag(0, vtkDICOMTag(0x0029, 0x1010), "SIEMENS CSA HEADER");
  const vtkDICOMValue& csa = meta->Get(0, tag);
  const unsigned char* bytes = csa.IsValid() ? csa.GetUnsignedCharData() : nullptr;
  const std::size_t size = bytes ? csa.GetNumberOfValues() : 0;
  return unpackMosaic(std::move(volume), bytes, size,
                      meta->Get(0, DC::SpacingBetweenSlices).AsDouble(),
                      meta->Get(0, DC::SliceThickness).AsDouble());
}

// vtk-dicom returns the frames of a multi-frame file that carries no per-frame position
// (RT dose grids with GridFrameOffsetVector, secondary captures) as vector components of a
// single slice. Frames are slices: stack them along the slice normal.
Volume stackFramesAsSlices(const Volume& in, int frames, int spp, vtkDICOMMetaData* meta) {
  const glm::ivec3 d = in.dimensions();
  Volume out({d.x, d.y, frames}, spp, in.scalarType(), in.worldFromIndex());
  out.metadata() = in.metadata();
  const std::size_t value = scalarSize(in.scalarType());
  const std::size_t pixelBytes = static_cast<std::size_t>(spp) * value;
  for (int f = 0; f < frames; ++f)
    for (std::size_t p = 0; p < static_cast<std::size_t>(d.x) * d.y; ++p)
      std::memcpy(out.data() + (static_cast<std::size_t>(f) * d.x * d.y + p) * pixelBytes,
                  in.data() + (p * frames + f) * pixelBytes, pixelBytes);
  const glm::dmat4& w = in.worldFromIndex();
  const glm::dvec3 normal = glm::normalize(glm::cross(glm::dvec3(w[0]), glm::dvec3(w[1])));
  const vtkDICOMValue& offsets = meta->Get(0, DC::GridFrameOffsetVector);
  glm::dmat4 m = w;
  if (offsets.GetNumberOfValues() == static_cast<std::size_t>(frames) && frames > 1) {
    const double step = offsets.GetDouble(1) - offsets.GetDouble(0);
    bool uniform = step != 0.0;
    for (int f = 2; f < frames; ++f)
      uniform &= std::abs(offsets.GetDouble(f) - offsets.GetDouble(f - 1) - step) <
                 1e-3 * std::abs(step) + 1e-4;
    m[2] = glm::dvec4(normal * step, 0.0);
    m[3] = w[3] + glm::dvec4(normal * offsets.GetDouble(0), 0.0);
    out.metadata().notes.push_back(
        std::string("frames stacked along the slice normal by GridFrameOffsetVector") +
        (uniform ? "" : " (NOT uniform: the volume uses the first step)"));
  } else {
    m[2] = glm::dvec4(normal, 0.0);
    out.metadata().notes.push_back("frames without positions stacked as slices 1 mm apart");
  }
  out.setWorldFromIndex(m);
  return out;
}

}  // namespace

bool numbersOk(const vtkDICOMValue& value, unsigned int count, double limit) {
  if (value.GetNumberOfValues() != count) return false;
  for (unsigned int i = 0; i < count; ++i) {
    const std::string text = value.GetString(i);
    const char* begin = text.c_str();
    char* end = nullptr;
    const double x = std::strtod(begin, &end);
    if (end == begin || !(std::abs(x) <= limit)) return false;
    while (*end == ' ') ++end;
    if (*end != '\0') return false;
  }
  return true;
}

std::optional<std::pair<glm::dvec3, glm::dvec3>> orientationAxes(const vtkDICOMValue& iop) {
  if (!numbersOk(iop, 6)) return std::nullopt;
  glm::dvec3 row, column;
  for (unsigned int a = 0; a < 3; ++a) {
    row[static_cast<int>(a)] = iop.GetDouble(a);
    column[static_cast<int>(a)] = iop.GetDouble(a + 3);
  }
  return std::pair{row, column};
}

glm::dmat4 patientWorldFromIndex(vtkDICOMReader* reader, vtkImageData* image) {
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  return patientWorldFromIndex(reader, origin, spacing);
}

glm::dmat4 patientWorldFromIndex(vtkDICOMReader* reader, const double origin[3],
                                 const double spacing[3]) {
  glm::dmat4 patientFromData(1.0);
  if (vtkMatrix4x4* p = reader->GetPatientMatrix()) {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) patientFromData[c][r] = p->GetElement(r, c);
  }
  glm::dmat4 dataFromIndex(1.0);
  for (int a = 0; a < 3; ++a) {
    dataFromIndex[a][a] = spacing[a] > 0 ? spacing[a] : 1.0;
    dataFromIndex[3][a] = origin[a];
  }
  return patientFromData * dataFromIndex;
}

Volume arrangeSlices(Volume volume, vtkDICOMReader* reader, bool singleFile,
                     const ReadOptions& options, const std::filesystem::path& first) {
  vtkDICOMMetaData* meta = reader->GetMetaData();
  const int spp = std::max(1, meta->Get(0, DC::SamplesPerPixel).AsInt());
  const int frames = meta->Get(0, DC::NumberOfFrames).AsInt();
  if (singleFile && frames > 1 && volume.dimensions().z == 1 && volume.components() == frames * spp)
    volume = stackFramesAsSlices(volume, frames, spp, meta);
  else if (singleFile && frames <= 1 && volume.dimensions().z == 1 && isMosaic(meta))
    volume = unpackMosaicFrom(std::move(volume), meta);
  else {
    const std::vector<glm::dvec3> positions = slicePositions(reader);
    if (positions.empty() && volume.dimensions().z > 1)
      volume = spaceUnplacedSlices(std::move(volume), meta);
    else
      volume =
          placeSlices(std::move(volume), positions, options.sliceSpacing, options.maxBytes, first);
  }
  return volume;
}

void noteGeometryFallbacks(Volume& volume, vtkDICOMMetaData* meta) {
  auto& md = volume.metadata();
  const vtkDICOMValue& iop = meta->Get(0, 0, DC::ImageOrientationPatient);
  if (iop.GetNumberOfValues() != 6) {
    md.notes.push_back("no ImageOrientationPatient: patient orientation unknown, axes assumed LPS");
  } else {
    // Two unit directions, at right angles; anything else was replaced by the reader.
    const auto axes = orientationAxes(iop);
    const bool usable = axes && std::abs(glm::length(axes->first) - 1.0) < 0.01 &&
                        std::abs(glm::length(axes->second) - 1.0) < 0.01 &&
                        std::abs(glm::dot(axes->first, axes->second)) < 0.01;
    if (!usable)
      md.notes.push_back("ImageOrientationPatient '" + iop.AsString() +
                         "' is not two perpendicular unit directions: axes assumed LPS");
  }
  // In-plane voxel size: a missing, zero, negative or non-numeric PixelSpacing was replaced.
  const vtkDICOMValue& ps = meta->Get(0, 0, DC::PixelSpacing);
  const bool spacingUsable = ps.GetNumberOfValues() == 2 && ps.GetDouble(0) > 0 &&
                             ps.GetDouble(1) > 0 && std::isfinite(ps.GetDouble(0)) &&
                             std::isfinite(ps.GetDouble(1));
  if (!spacingUsable) {
    char size[64];
    std::snprintf(size, sizeof size, "%g x %g mm", volume.spacing().x, volume.spacing().y);
    md.notes.push_back(
        (ps.IsValid() ? "PixelSpacing '" + ps.AsString() + "' is not usable" : "no PixelSpacing") +
        ": in-plane voxel size " + size + " assumed");
  }
}

}  // namespace mvw::io::detail
