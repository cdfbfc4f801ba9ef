// DICOM SEG through vtk-dicom's parser: the header (segments, per-frame positions, shared
// orientation and pixel measures) from vtkDICOMMetaData, the pixel data read here from the
// offset the parser reports, after checking its length against rows * columns * frames.
// Frames are placed on one slice grid along the plane normal by their ImagePositionPatient.
#include "mvw/io/DicomSeg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMTagPath.h>
#include <vtkDICOMValue.h>
#include <vtkNew.h>
#include <glm/geometric.hpp>

#include "DecoderGuard.h"
#include "DicomFile.h"
#include "FileChecks.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

namespace mvw::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kSegmentationStorage = "1.2.840.10008.5.1.4.1.1.66.4";

// A value of the first (and only) item of a functional group, per frame or shared.
const vtkDICOMValue& groupValue(vtkDICOMMetaData* meta, vtkDICOMTag groups, unsigned frame,
                                vtkDICOMTag sequence, vtkDICOMTag tag) {
  return meta->Get(vtkDICOMTagPath(groups, frame, sequence, 0, tag));
}

// A functional-group value from the frame's own group, else the shared group.
const vtkDICOMValue& frameValue(vtkDICOMMetaData* meta, unsigned frame, vtkDICOMTag sequence,
                                vtkDICOMTag tag) {
  const vtkDICOMValue& own =
      groupValue(meta, DC::PerFrameFunctionalGroupsSequence, frame, sequence, tag);
  if (own.IsValid()) return own;
  return groupValue(meta, DC::SharedFunctionalGroupsSequence, 0, sequence, tag);
}

bool finite3(const vtkDICOMValue& v) {
  if (v.GetNumberOfValues() != 3) return false;
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v.GetDouble(i))) return false;
  return true;
}

double srgbGamma(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

}  // namespace

std::array<std::uint8_t, 3> srgbFromDicomLab(std::uint16_t l16, std::uint16_t a16,
                                             std::uint16_t b16) {
  const double l = l16 * 100.0 / 65535.0;
  const double a = a16 * 255.0 / 65535.0 - 128.0;
  const double b = b16 * 255.0 / 65535.0 - 128.0;
  // CIELab -> XYZ (D65 white, as dcmqi and 3D Slicer convert), XYZ -> linear sRGB.
  const double fy = (l + 16.0) / 116.0, fx = fy + a / 500.0, fz = fy - b / 200.0;
  auto finv = [](double t) {
    return t > 6.0 / 29.0 ? t * t * t : 3.0 * (6.0 / 29.0) * (6.0 / 29.0) * (t - 4.0 / 29.0);
  };
  const double x = 0.95047 * finv(fx), y = 1.0 * finv(fy), z = 1.08883 * finv(fz);
  const double r = 3.2404542 * x - 1.5371385 * y - 0.4985314 * z;
  const double g = -0.9692660 * x + 1.8760108 * y + 0.0415560 * z;
  const double bl = 0.0556434 * x - 0.2040259 * y + 1.0572252 * z;
  auto byte = [](double v) { return static_cast<std::uint8_t>(std::lround(srgbGamma(v) * 255.0)); };
  return {byte(r), byte(g), byte(bl)};
}

bool isDicomSegmentation(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  try {
    detail::DecoderGuard guard(path);
    vtkNew<vtkDICOMMetaData> meta;
    detail::parseDicomFile(path, meta);
    return meta->Get(DC::SOPClassUID).AsString() == kSegmentationStorage;
  } catch (const InputError&) {
    return false;
  }
}

Segmentation readDicomSegmentation(const fs::path& path, const ReadOptions& options) {
  detail::DecoderGuard guard(path, options.isolateDecoder);
  vtkNew<vtkDICOMMetaData> meta;
  const detail::ParsedDicomFile parsed = detail::parseDicomFile(path, meta);
  return detail::segmentationFromHeader(path, meta, parsed, options);
}

namespace {

// The SegmentSequence into seg.segments. Returns each segment number's component (the
// segment's index).
std::map<int, int> readSegments(const fs::path& path, vtkDICOMMetaData* meta, Segmentation& seg) {
  const vtkDICOMValue& segments = meta->Get(DC::SegmentSequence);
  const std::size_t segmentCount = segments.GetNumberOfValues();
  if (segmentCount == 0) throw InputError(path, "SEG: no SegmentSequence");
  if (segmentCount > 255)
    throw InputError(path, "SEG: " + std::to_string(segmentCount) + " segments (at most 255)");
  std::map<int, int> componentOf;
  for (std::size_t s = 0; s < segmentCount; ++s) {
    const auto i = static_cast<unsigned>(s);
    Segment out;
    const vtkDICOMValue& number =
        meta->Get(vtkDICOMTagPath(DC::SegmentSequence, i, DC::SegmentNumber));
    if (!number.IsValid() || number.AsInt() <= 0)
      throw InputError(
          path, "SEG: segment item " + std::to_string(s + 1) + " has no positive SegmentNumber");
    out.number = number.AsInt();
    out.label = meta->Get(vtkDICOMTagPath(DC::SegmentSequence, i, DC::SegmentLabel)).AsString();
    out.description =
        meta->Get(vtkDICOMTagPath(DC::SegmentSequence, i, DC::SegmentDescription)).AsString();
    const vtkDICOMValue& lab =
        meta->Get(vtkDICOMTagPath(DC::SegmentSequence, i, DC::RecommendedDisplayCIELabValue));
    if (lab.GetNumberOfValues() == 3)
      out.rgb = srgbFromDicomLab(static_cast<std::uint16_t>(lab.GetUnsignedShort(0)),
                                 static_cast<std::uint16_t>(lab.GetUnsignedShort(1)),
                                 static_cast<std::uint16_t>(lab.GetUnsignedShort(2)));
    if (!componentOf.emplace(out.number, static_cast<int>(s)).second)
      throw InputError(path, "SEG: segment number " + std::to_string(out.number) + " repeated");
    seg.segments.push_back(out);
  }
  return componentOf;
}

// The plane every frame lies in: unit row and column directions, their normal, and the
// pixel spacing along a row (i) and a column (j).
struct FramePlane {
  glm::dvec3 rowDir, colDir, normal;
  double spacingI = 0.0, spacingJ = 0.0;
};

// One orientation and pixel spacing for all frames (shared, or the first frame's).
FramePlane framePlane(const fs::path& path, vtkDICOMMetaData* meta, long long frames) {
  if (meta->Get(DC::PerFrameFunctionalGroupsSequence).GetNumberOfValues() !=
      static_cast<std::size_t>(frames))
    throw InputError(
        path,
        "SEG: PerFrameFunctionalGroupsSequence has " +
            std::to_string(meta->Get(DC::PerFrameFunctionalGroupsSequence).GetNumberOfValues()) +
            " items for " + std::to_string(frames) + " frames");
  const vtkDICOMValue& iop =
      frameValue(meta, 0, DC::PlaneOrientationSequence, DC::ImageOrientationPatient);
  const vtkDICOMValue& ps = frameValue(meta, 0, DC::PixelMeasuresSequence, DC::PixelSpacing);
  if (iop.GetNumberOfValues() != 6 || ps.GetNumberOfValues() != 2)
    throw InputError(path,
                     "SEG: no ImageOrientationPatient or PixelSpacing in the functional "
                     "groups (PlaneOrientationSequence, PixelMeasuresSequence)");
  glm::dvec3 rowDir{iop.GetDouble(0), iop.GetDouble(1), iop.GetDouble(2)};
  glm::dvec3 colDir{iop.GetDouble(3), iop.GetDouble(4), iop.GetDouble(5)};
  const double spacingJ = ps.GetDouble(0), spacingI = ps.GetDouble(1);
  if (!(glm::length(rowDir) > 0.5 && glm::length(colDir) > 0.5 &&
        std::abs(glm::dot(glm::normalize(rowDir), glm::normalize(colDir))) < 1e-3) ||
      !std::isfinite(glm::length(rowDir) + glm::length(colDir)))
    throw InputError(path, "SEG: ImageOrientationPatient is not two orthogonal directions");
  if (!(spacingI > 0 && spacingJ > 0 && std::isfinite(spacingI) && std::isfinite(spacingJ)))
    throw InputError(path, "SEG: PixelSpacing not positive");
  rowDir = glm::normalize(rowDir);
  colDir = glm::normalize(colDir);
  return {rowDir, colDir, glm::cross(rowDir, colDir), spacingI, spacingJ};
}

// Each frame's ImagePositionPatient and the component of the segment it carries (counted in
// that segment's frames).
struct FrameRefs {
  std::vector<glm::dvec3> positions;
  std::vector<int> component;
};

FrameRefs frameRefs(const fs::path& path, vtkDICOMMetaData* meta, long long frames,
                    const std::map<int, int>& componentOf, Segmentation& seg) {
  FrameRefs refs;
  refs.positions.resize(static_cast<std::size_t>(frames));
  refs.component.resize(static_cast<std::size_t>(frames));
  for (long long f = 0; f < frames; ++f) {
    const auto u = static_cast<unsigned>(f);
    const vtkDICOMValue& ipp = groupValue(meta, DC::PerFrameFunctionalGroupsSequence, u,
                                          DC::PlanePositionSequence, DC::ImagePositionPatient);
    if (!finite3(ipp))
      throw InputError(path,
                       "SEG: frame " + std::to_string(f + 1) + " has no ImagePositionPatient");
    refs.positions[u] = {ipp.GetDouble(0), ipp.GetDouble(1), ipp.GetDouble(2)};
    const vtkDICOMValue& ref =
        groupValue(meta, DC::PerFrameFunctionalGroupsSequence, u, DC::SegmentIdentificationSequence,
                   DC::ReferencedSegmentNumber);
    const auto it = componentOf.find(ref.IsValid() ? ref.AsInt() : -1);
    if (it == componentOf.end())
      throw InputError(path, "SEG: frame " + std::to_string(f + 1) +
                                 " refers to no segment of the SegmentSequence");
    refs.component[u] = it->second;
    ++seg.segments[static_cast<std::size_t>(it->second)].frames;
  }
  return refs;
}

// The slice grid the frames lie on: voxel 0's position, the slice distance, the number of
// slices and each frame's slice.
struct SliceGrid {
  glm::dvec3 origin;
  double step = 1.0;
  int slices = 0;
  std::vector<int> frameSlice;
};

// The slice distance: SpacingBetweenSlices, else the smallest gap between frame depths (in
// `sorted` order) above `tolerance`, else SliceThickness, else 1 mm.
double sliceStep(vtkDICOMMetaData* meta, const std::vector<double>& sorted, double tolerance) {
  double step = frameValue(meta, 0, DC::PixelMeasuresSequence, DC::SpacingBetweenSlices).AsDouble();
  if (!(step > 0 && std::isfinite(step))) {
    step = 0;
    for (std::size_t i = 1; i < sorted.size(); ++i)
      if (sorted[i] - sorted[i - 1] > tolerance && (step == 0 || sorted[i] - sorted[i - 1] < step))
        step = sorted[i] - sorted[i - 1];
    if (step == 0)
      step = frameValue(meta, 0, DC::PixelMeasuresSequence, DC::SliceThickness).AsDouble();
    if (!(step > 0 && std::isfinite(step))) step = 1.0;
  }
  return step;
}

// All frames must share the in-plane origin; their distance along the normal picks the slice.
SliceGrid sliceGrid(const fs::path& path, vtkDICOMMetaData* meta,
                    const std::vector<glm::dvec3>& positions, const FramePlane& plane) {
  const glm::dvec3 normal = plane.normal;
  const glm::dvec3 inPlane0 = positions[0] - glm::dot(positions[0], normal) * normal;
  const double tolerance = 0.05 * std::min(plane.spacingI, plane.spacingJ) + 1e-3;
  std::vector<double> depth(positions.size());
  for (std::size_t f = 0; f < positions.size(); ++f) {
    depth[f] = glm::dot(positions[f], normal);
    if (glm::length(positions[f] - depth[f] * normal - inPlane0) > tolerance)
      throw InputError(path, "SEG: frame " + std::to_string(f + 1) +
                                 " is shifted within its plane from frame 1 (frames on different "
                                 "grids are not supported)");
  }
  std::vector<double> sorted = depth;
  std::sort(sorted.begin(), sorted.end());
  SliceGrid grid;
  const double step = sliceStep(meta, sorted, tolerance);
  const double span = (sorted.back() - sorted.front()) / step;
  if (!(span < (1 << 16)))
    throw InputError(path,
                     "SEG: frames span more than 65536 slices of " + std::to_string(step) + " mm");
  grid.step = step;
  grid.slices = static_cast<int>(std::lround(span)) + 1;
  grid.frameSlice.resize(positions.size());
  for (std::size_t f = 0; f < positions.size(); ++f) {
    const double k = (depth[f] - sorted.front()) / step;
    grid.frameSlice[f] = static_cast<int>(std::lround(k));
    if (std::abs(k - grid.frameSlice[f]) * step > 0.1 * step + 1e-3)
      throw InputError(path, "SEG: frame " + std::to_string(f + 1) +
                                 " lies between the slices of a " + std::to_string(step) +
                                 " mm grid");
  }
  // Voxel 0: the slice index runs along the normal from the lowest frame.
  grid.origin = inPlane0 + sorted.front() * normal;
  return grid;
}

// Pixel data: native (not encapsulated), rows * cols * frames * bits / 8 bytes, in the file.
std::vector<std::uint8_t> readPixelData(const fs::path& path, const detail::ParsedDicomFile& parsed,
                                        long long rows, long long cols, long long frames,
                                        long long bits, std::uintmax_t fileSize) {
  if (!parsed.pixelData) throw InputError(path, "SEG: no pixel data");
  if (parsed.pixelLength == 0xffffffffu)
    throw InputError(path, "SEG: compressed (encapsulated) pixel data is not supported");
  const std::size_t framePixels = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  const std::size_t totalPixels = framePixels * static_cast<std::size_t>(frames);
  const std::size_t need = bits == 1 ? (totalPixels + 7) / 8 : totalPixels;
  if (parsed.pixelLength < need || parsed.pixelOffset < 0 ||
      static_cast<std::uintmax_t>(parsed.pixelOffset) + need > fileSize)
    throw InputError(
        path,
        "SEG: truncated: " + std::to_string(rows) + " x " + std::to_string(cols) + " x " +
            std::to_string(frames) + " frames need " + std::to_string(need) +
            " bytes of pixel data, the file holds " +
            std::to_string(std::min<std::uintmax_t>(
                parsed.pixelLength, fileSize > static_cast<std::uintmax_t>(parsed.pixelOffset)
                                        ? fileSize - static_cast<std::uintmax_t>(parsed.pixelOffset)
                                        : 0)));
  std::vector<std::uint8_t> pixels(need);
  std::ifstream in(path, std::ios::binary);
  in.seekg(parsed.pixelOffset);
  if (!in.read(reinterpret_cast<char*>(pixels.data()), static_cast<std::streamsize>(need)))
    throw InputError(path, "SEG: cannot read the pixel data");
  return pixels;
}

}  // namespace

Segmentation detail::segmentationFromHeader(const fs::path& path, vtkDICOMMetaData* meta,
                                            const ParsedDicomFile& parsed,
                                            const ReadOptions& given) {
  const std::size_t maxBytes = given.maxBytes ? given.maxBytes : defaultMaxBytes();
  const std::uintmax_t fileSize = detail::regularFileSize(path);
  if (meta->Get(DC::SOPClassUID).AsString() != kSegmentationStorage)
    throw InputError(path, "not a DICOM Segmentation (SOPClassUID " +
                               meta->Get(DC::SOPClassUID).AsString() + ")");
  Segmentation seg;
  seg.type = meta->Get(DC::SegmentationType).AsString();
  seg.frameOfReferenceUid = meta->Get(DC::FrameOfReferenceUID).AsString();
  const long long rows = meta->Get(DC::Rows).AsInt64();
  const long long cols = meta->Get(DC::Columns).AsInt64();
  const long long frames = meta->Get(DC::NumberOfFrames).AsInt64();
  const long long bits = meta->Get(DC::BitsAllocated).AsInt64();
  if (rows <= 0 || cols <= 0 || rows > 65535 || cols > 65535)
    throw InputError(path, "SEG: Rows or Columns missing or out of range");
  if (frames <= 0 || frames > (1 << 20))
    throw InputError(path,
                     "SEG: NumberOfFrames missing or implausible (" + std::to_string(frames) + ")");
  if (seg.type == "BINARY" ? bits != 1 : seg.type == "FRACTIONAL" ? bits != 8 : true)
    throw InputError(path, "SEG: unsupported SegmentationType '" + seg.type +
                               "' with BitsAllocated " + std::to_string(bits) +
                               " (expected BINARY 1-bit or FRACTIONAL 8-bit)");
  seg.frames = static_cast<int>(frames);

  const std::map<int, int> componentOf = readSegments(path, meta, seg);
  const FramePlane plane = framePlane(path, meta, frames);
  const FrameRefs refs = frameRefs(path, meta, frames, componentOf, seg);
  const SliceGrid grid = sliceGrid(path, meta, refs.positions, plane);

  const glm::ivec3 dims{static_cast<int>(cols), static_cast<int>(rows), grid.slices};
  const int components = static_cast<int>(seg.segments.size());
  detail::checkedVolumeBytes(path, dims, components, 1, maxBytes);
  const std::vector<std::uint8_t> pixels =
      readPixelData(path, parsed, rows, cols, frames, bits, fileSize);

  double maxFraction = meta->Get(DC::MaximumFractionalValue).AsDouble();
  if (!(maxFraction > 0)) maxFraction = 255.0;

  // World placement: column index along the row direction, row index along the column
  // direction, slice index along the normal from the lowest frame.
  glm::dmat3 direction(plane.rowDir, plane.colDir, plane.normal);
  seg.masks = Volume(
      dims, components, ScalarType::UInt8,
      makeWorldFromIndex(grid.origin, {plane.spacingI, plane.spacingJ, grid.step}, direction));
  const std::size_t framePixels = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  std::uint8_t* out = seg.masks.dataAs<std::uint8_t>();
  for (std::size_t f = 0; f < refs.positions.size(); ++f) {
    const std::size_t sliceBase = static_cast<std::size_t>(grid.frameSlice[f]) * framePixels;
    for (std::size_t p = 0; p < framePixels; ++p) {
      const std::size_t bit = f * framePixels + p;
      const bool inside = bits == 1 ? ((pixels[bit >> 3] >> (bit & 7)) & 1) != 0
                                    : pixels[bit] * 2.0 >= maxFraction && pixels[bit] > 0;
      if (inside)
        out[(sliceBase + p) * static_cast<std::size_t>(components) +
            static_cast<std::size_t>(refs.component[f])] = 1;
    }
  }
  auto& md = seg.masks.metadata();
  md.format = "DICOM";
  md.modality = "SEG";
  md.sourcePath = path.string();
  md.seriesInstanceUid = meta->Get(DC::SeriesInstanceUID).AsString();
  md.seriesDescription = meta->Get(DC::SeriesDescription).AsString();
  md.seriesNumber =
      meta->Get(DC::SeriesNumber).IsValid() ? meta->Get(DC::SeriesNumber).AsInt() : -1;
  md.frameOfReferenceUid = seg.frameOfReferenceUid;
  return seg;
}

Volume labelVolume(const Segmentation& seg) {
  const Volume& masks = seg.masks;
  int highest = 0;
  for (const auto& s : seg.segments) highest = std::max(highest, s.number);
  const ScalarType type = highest <= 255 ? ScalarType::UInt8 : ScalarType::UInt16;
  Volume out(masks.dimensions(), 1, type, masks.worldFromIndex());
  out.metadata() = masks.metadata();
  const std::size_t n = masks.voxelCount();
  const auto c = static_cast<std::size_t>(masks.components());
  const std::uint8_t* in = masks.dataAs<std::uint8_t>();
  std::size_t overlapping = 0;
  for (std::size_t v = 0; v < n; ++v) {
    int label = 0, count = 0;
    for (std::size_t s = 0; s < c; ++s)
      if (in[v * c + s]) {
        label = std::max(label, seg.segments[s].number);
        ++count;
      }
    if (count > 1) ++overlapping;
    if (type == ScalarType::UInt8)
      out.dataAs<std::uint8_t>()[v] = static_cast<std::uint8_t>(label);
    else
      out.dataAs<std::uint16_t>()[v] = static_cast<std::uint16_t>(label);
  }
  auto& notes = out.metadata().notes;
  notes.push_back("DICOM SEG (" + seg.type + "), " + countOf(seg.frames, "frame") + ", " +
                  countOf(static_cast<long long>(seg.segments.size()), "segment") +
                  "; values are segment numbers (0: none)");
  for (const auto& s : seg.segments) {
    std::string line = "segment " + std::to_string(s.number) + " \"" + s.label + "\", " +
                       countOf(s.frames, "frame");
    if (s.rgb) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "#%02x%02x%02x", (*s.rgb)[0], (*s.rgb)[1], (*s.rgb)[2]);
      line += ", colour " + std::string(hex);
    }
    notes.push_back(line);
  }
  if (overlapping)
    notes.push_back(countOf(static_cast<long long>(overlapping), "voxel") +
                    (overlapping == 1 ? " lies" : " lie") +
                    " in more than one segment: labelled with the highest number");
  return out;
}

}  // namespace mvw::io
