#pragma once
// A volume: typed voxels plus the geometry that puts them in the patient's world.
// World coordinates are LPS millimetres as in DICOM; worldFromIndex maps a voxel index
// (i, j, k, 1) to the voxel centre in LPS mm and carries origin, spacing and direction.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/core/ScalarType.h"

namespace mvw {

// How regular the slice positions of a series are (DICOM); empty for formats with one spacing.
struct SliceSpacing {
  int slices = 0;
  double nominal = 0.0;  // median distance between neighbouring slices, mm
  double minimum = 0.0;
  double maximum = 0.0;
  bool regular = true;  // every gap within 1 % (and 0.01 mm) of the nominal
  // The acquired slices (described above) were resampled onto the volume's regular grid:
  // uneven or missing slices, or gantry tilt (see the notes).
  bool resampled = false;
};

struct VolumeMetadata {
  std::string modality;  // DICOM modality code: CT, MR, PT, NM, ... ("" if unknown)
  std::string unit;      // physical unit of the values: HU, Bq/ml, SUVbw, ... ("" if none)
  std::string format;    // DICOM, NIfTI-1, NIfTI-2, MetaImage
  std::string sourcePath;
  std::string seriesInstanceUid;  // DICOM only
  std::string seriesDescription;
  std::string frameOfReferenceUid;  // DICOM only
  int seriesNumber = -1;
  std::optional<SliceSpacing> sliceSpacing;
  std::optional<double> suvFactor;  // PET read as SUVbw: SUVbw = Bq/ml x suvFactor
  std::vector<std::string> notes;   // what a user should know: unit decisions, reorderings
  // DICOM only: the SEG files beside the one image series of a folder that holds both (the
  // series read without --series); a tool may offer them as the volume's segmentation.
  std::vector<std::string> segmentationFiles;
};

class Volume {
 public:
  Volume() = default;
  // Allocates dims.x*dims.y*dims.z*components voxels, zeroed. Components are interleaved
  // (the fastest index), as in VTK: time frames of a 4D series or colour channels.
  Volume(glm::ivec3 dims, int components, ScalarType type, const glm::dmat4& worldFromIndex);

  glm::ivec3 dimensions() const { return dims_; }
  int components() const { return components_; }
  ScalarType scalarType() const { return type_; }
  std::size_t voxelCount() const;  // spatial voxels, without components
  std::size_t valueCount() const { return voxelCount() * static_cast<std::size_t>(components_); }
  std::size_t byteSize() const { return bytes_.size(); }
  bool empty() const { return bytes_.empty(); }

  std::byte* data() { return bytes_.data(); }
  const std::byte* data() const { return bytes_.data(); }
  template <class T>
  T* dataAs();
  template <class T>
  const T* dataAs() const;

  std::size_t linearIndex(int i, int j, int k) const;
  double value(int i, int j, int k, int component = 0) const;  // any type, as double
  void setValue(int i, int j, int k, int component, double v);

  const glm::dmat4& worldFromIndex() const { return worldFromIndex_; }
  void setWorldFromIndex(const glm::dmat4& m) { worldFromIndex_ = m; }
  glm::dvec3 origin() const;       // world position of voxel (0,0,0), LPS mm
  glm::dvec3 spacing() const;      // mm between voxel centres along i, j, k
  double smallestSpacing() const;  // the finest of the three (the default step's reference)
  glm::dmat3 direction() const;    // unit columns: world direction of i, j, k
  glm::dvec3 worldFromIndexPoint(const glm::dvec3& ijk) const;

  // min and max over all voxels and components, NaN ("no data") and +-inf ignored: always
  // finite; {0,0} for an empty or all-NaN volume.
  std::pair<double, double> valueRange() const;

  VolumeMetadata& metadata() { return meta_; }
  const VolumeMetadata& metadata() const { return meta_; }

  // A new volume of another scalar type with value' = value * slope + intercept.
  Volume converted(ScalarType type, double slope = 1.0, double intercept = 0.0) const;

 private:
  glm::ivec3 dims_{0};
  int components_ = 1;
  ScalarType type_ = ScalarType::UInt8;
  std::vector<std::byte> bytes_;
  glm::dmat4 worldFromIndex_{1.0};
  VolumeMetadata meta_;
};

// origin + direction * diag(spacing): the usual way geometry arrives from a file header.
glm::dmat4 makeWorldFromIndex(const glm::dvec3& origin, const glm::dvec3& spacing,
                              const glm::dmat3& direction);

template <class T>
T* Volume::dataAs() {
  return scalarTypeOf<T>() == type_ ? reinterpret_cast<T*>(bytes_.data()) : nullptr;
}
template <class T>
const T* Volume::dataAs() const {
  return scalarTypeOf<T>() == type_ ? reinterpret_cast<const T*>(bytes_.data()) : nullptr;
}

}  // namespace mvw
