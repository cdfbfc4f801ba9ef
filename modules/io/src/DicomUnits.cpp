// RescaleSlope and RescaleIntercept are per file (and per frame): a series may carry a slope
// per slice, and vtk-dicom applies each slice's own.
#include "DicomUnits.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMValue.h>
#include <vtkDataArray.h>
#include <vtkIntArray.h>

#include "DicomSuv.h"

namespace mvw::io::detail {

namespace {

// The RescaleSlope of one file's frame (1 where it is missing, zero or not finite: such a
// slope is not applied, and noteRescale says so) and its RescaleIntercept as stored.
std::pair<double, double> rescaleOf(vtkDICOMMetaData* meta, int file, int frame) {
  const vtkDICOMValue& s = meta->Get(file, frame, DC::RescaleSlope);
  double slope = s.IsValid() ? s.AsDouble() : 1.0;
  if (!std::isfinite(slope) || slope == 0.0) slope = 1.0;
  return {slope, meta->Get(file, frame, DC::RescaleIntercept).AsDouble()};
}

}  // namespace

bool rescaleMayClip(vtkDICOMMetaData* meta, vtkIntArray* fileIndex, vtkIntArray* frameIndex,
                    int vtkType) {
  if (vtkType == VTK_FLOAT || vtkType == VTK_DOUBLE || !fileIndex || !frameIndex) return false;
  const double lo = vtkDataArray::GetDataTypeMin(vtkType),
               hi = vtkDataArray::GetDataTypeMax(vtkType);
  for (vtkIdType t = 0; t < fileIndex->GetNumberOfTuples(); ++t)
    for (int c = 0; c < fileIndex->GetNumberOfComponents(); ++c) {
      const int f = fileIndex->GetComponent(t, c), frame = frameIndex->GetComponent(t, c);
      const auto [slope, intercept] = rescaleOf(meta, f, frame);
      if (slope == 1.0) continue;
      int bits = meta->Get(f, DC::BitsStored).AsInt();
      if (bits < 1 || bits > 32) bits = meta->Get(f, DC::BitsAllocated).AsInt();
      if (bits < 1 || bits > 32) continue;
      const bool isSigned = meta->Get(f, DC::PixelRepresentation).AsInt() == 1;
      const double storedMin = isSigned ? -std::ldexp(1.0, bits - 1) : 0.0;
      const double storedMax =
          isSigned ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
      const double a = slope * storedMin + intercept, b = slope * storedMax + intercept;
      if (std::min(a, b) < lo - 0.5 || std::max(a, b) > hi + 0.5) return true;
    }
  return false;
}

Volume rescaleSlices(const Volume& volume, vtkDICOMMetaData* meta, vtkIntArray* fileIndex,
                     vtkIntArray* frameIndex, int samplesPerPixel) {
  const glm::ivec3 d = volume.dimensions();
  const int comps = volume.components();
  Volume out(d, comps, ScalarType::Float32, volume.worldFromIndex());
  out.metadata() = volume.metadata();
  const std::size_t plane = static_cast<std::size_t>(d.x) * d.y;
  float* dst = out.dataAs<float>();
  dispatchScalar(volume.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* src = volume.dataAs<T>();
    for (int k = 0; k < d.z; ++k)
      for (int c = 0; c < comps; ++c) {
        const int time =
            std::min(c / std::max(samplesPerPixel, 1), fileIndex->GetNumberOfComponents() - 1);
        const int f = fileIndex->GetComponent(k, time), frame = frameIndex->GetComponent(k, time);
        auto [slope, intercept] = rescaleOf(meta, f, frame);
        if (!std::isfinite(intercept)) intercept = 0.0;
        const std::size_t base = static_cast<std::size_t>(k) * plane * comps + c;
        for (std::size_t p = 0; p < plane; ++p)
          dst[base + p * comps] =
              static_cast<float>(static_cast<double>(src[base + p * comps]) * slope + intercept);
      }
    return 0;
  });
  return out;
}

void noteRescale(Volume& volume, vtkDICOMMetaData* meta, bool rescaledHere) {
  auto& md = volume.metadata();
  const vtkDICOMValue& slope = meta->Get(0, 0, DC::RescaleSlope);
  if (rescaledHere)
    md.notes.push_back(
        "RescaleSlope and RescaleIntercept applied here, to float32: on the "
        "stored values' range they could leave the reader's integer type");
  if (slope.IsValid() && !(std::isfinite(slope.GetDouble(0)) && slope.GetDouble(0) != 0.0))
    md.notes.push_back("RescaleSlope '" + slope.AsString() +
                       "' is not a usable factor: the stored values were not rescaled by it");
}

void fillUnitAndSuv(Volume& volume, vtkDICOMMetaData* meta, const ReadOptions& options) {
  auto& md = volume.metadata();
  const std::string rescaleType = meta->Get(0, DC::RescaleType).AsString();
  if (md.modality == "CT") {
    md.unit = rescaleType.empty() ? "HU" : rescaleType;
    return;
  }
  if (md.modality == "RTDOSE") {
    const double scaling = meta->Get(0, DC::DoseGridScaling).AsDouble();
    const std::string units = meta->Get(0, DC::DoseUnits).AsString();
    md.unit = units == "GY" ? "Gy" : units == "RELATIVE" ? "%" : units;
    if (scaling > 0 && std::isfinite(scaling) && scaling != 1.0) {
      VolumeMetadata keep = md;
      volume = volume.converted(ScalarType::Float32, scaling, 0.0);
      volume.metadata() = keep;
      volume.metadata().notes.push_back("DoseGridScaling " +
                                        meta->Get(0, DC::DoseGridScaling).AsString() + " applied");
    }
    return;
  }
  if (md.modality != "PT") {
    md.unit = rescaleType == "US" ? "" : rescaleType;
    return;
  }
  fillPetUnitAndSuv(volume, meta, options);
}

}  // namespace mvw::io::detail
