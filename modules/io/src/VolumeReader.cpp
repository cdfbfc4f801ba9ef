#include "mvw/io/VolumeReader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "FileChecks.h"
#include "Formats.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

namespace mvw::io {

std::string maxBytesProblem(const std::string& bytes) {
  errno = 0;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(bytes.c_str(), &end, 10);
  if (errno != 0 || end == bytes.c_str() || *end != '\0' || n < (1ull << 20) || n > (1ull << 50))
    return "must be a size from 1M to 1P (e.g. 512M, 4G)";
  return "";
}

namespace fs = std::filesystem;

std::size_t defaultMaxBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return std::size_t{4} << 30;
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(pageSize) / 4;
}

FileFormat detectFormat(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return FileFormat::Dicom;
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  auto ends = [&](const char* s) {
    const std::string suffix(s);
    return name.size() >= suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends(".nii") || ends(".nii.gz") || ends(".hdr") || ends(".hdr.gz")) return FileFormat::Nifti;
  if (ends(".mha") || ends(".mhd")) return FileFormat::MetaImage;
  if (ends(".dcm") || ends(".ima") || path.extension().empty()) return FileFormat::Dicom;
  // Unknown extension: DICOM files carry "DICM" at byte 128 (most of them).
  std::ifstream in(path, std::ios::binary);
  char magic[132] = {};
  if (in.read(magic, sizeof magic) && std::string(magic + 128, 4) == "DICM")
    return FileFormat::Dicom;
  return FileFormat::Unknown;
}

namespace {

// A float volume without one finite voxel is refused. +-inf voxels are clamped to the finite range
// of the others, with a note, rather than the file refused: a few infinite voxels (a ratio map
// divided by zero, a failed fit) should not make a whole scan unreadable, and left in they break
// every window, transfer function and histogram downstream. They are not made NaN: NaN means "no
// data", which an overflow is not.
void clampInfinities(Volume& volume, const fs::path& path) {
  if (volume.scalarType() != ScalarType::Float32 && volume.scalarType() != ScalarType::Float64)
    return;
  dispatchScalar(volume.scalarType(), [&](auto t) {
    using T = decltype(t);
    if constexpr (std::is_floating_point_v<T>) {
      T* p = volume.dataAs<T>();
      const std::size_t n = volume.valueCount();
      std::size_t plus = 0, minus = 0;
      T lo = std::numeric_limits<T>::infinity(), hi = -lo;
      for (std::size_t i = 0; i < n; ++i) {
        if (std::isinf(p[i])) {
          (p[i] > 0 ? plus : minus) += 1;
        } else if (!std::isnan(p[i])) {
          lo = std::min(lo, p[i]);
          hi = std::max(hi, p[i]);
        }
      }
      // Without one finite voxel (all NaN, all infinite) the file holds no image.
      if (lo > hi) throw InputError(path, "no finite voxel value: every voxel is infinite or NaN");
      if (plus + minus == 0) return;
      for (std::size_t i = 0; i < n; ++i)
        if (std::isinf(p[i])) p[i] = p[i] > 0 ? hi : lo;
      std::string note;
      if (plus)
        note = countOf(static_cast<long long>(plus), "voxel") +
               " +inf clamped to the largest finite value " + shortNumber(hi);
      if (minus) {
        if (!note.empty()) note += "; ";
        note += countOf(static_cast<long long>(minus), "voxel") +
                " -inf clamped to the smallest finite value " + shortNumber(lo);
      }
      volume.metadata().notes.push_back(note);
    }
  });
}

// Every reader's geometry, checked once: finite, three independent axes, voxel sizes and a
// position a scanner can have. Beyond these the grid arithmetic downstream (sample grids,
// ray steps, glyph spacing) would divide by nothing or allocate without bound.
void checkGeometry(const Volume& volume, const fs::path& path) {
  const glm::dmat4& m = volume.worldFromIndex();
  const detail::GeometryProblem problem = detail::geometryProblem(m);
  if (problem == detail::GeometryProblem::NotFinite)
    throw InputError(path, "its geometry (voxel axes and origin) is not finite");
  const glm::dvec3 spacing = volume.spacing();
  for (int a = 0; a < 3; ++a)
    if (!(spacing[a] >= 1e-6 && spacing[a] <= 1e6))
      throw InputError(path, "voxel size " + shortNumber(spacing[a]) + " mm along axis " +
                                 std::to_string(a + 1) + " is not a voxel size (1e-6 .. 1e6 mm)");
  if (problem == detail::GeometryProblem::Singular)
    throw InputError(path, "its voxel axes are parallel (a singular orientation)");
  const glm::dvec3 origin(m[3]);
  for (int a = 0; a < 3; ++a)
    if (std::abs(origin[a]) > 1e6)
      throw InputError(path, "its origin " + shortNumber(origin[a]) + " mm along " + "xyz"[a] +
                                 " lies beyond 1 km: not a position in a scanner");
}

// A path with nothing to read behind it, said as what it is.
void refuseMissing(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) requireReadable(path);  // always a reason: says which
}

// Voxel axes that are not perpendicular (a NIfTI sform or MetaImage matrix with shear, e.g. a
// gantry-tilted scan stored without resampling) are kept as given, with a note: rendering,
// resampling and shading normals (render::VolumeTextures) follow the whole matrix, but a
// NIfTI qform (written by `mvw convert` beside the sform) cannot hold a shear.
void noteShear(Volume& volume) {
  const glm::dmat4& m = volume.worldFromIndex();
  std::string angles;
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const glm::dvec3 u = glm::normalize(glm::dvec3(m[a])), v = glm::normalize(glm::dvec3(m[b]));
      const double degrees =
          std::acos(std::clamp(glm::dot(u, v), -1.0, 1.0)) * 180.0 / std::numbers::pi;
      if (std::abs(degrees - 90.0) > 0.01)
        angles += std::string(angles.empty() ? "" : ", ") + "ijk"[a] + "-" + "ijk"[b] + " " +
                  shortNumber(degrees, 4) + " degrees";
    }
  if (!angles.empty())
    volume.metadata().notes.push_back("its voxel axes are not perpendicular (" + angles +
                                      "): a sheared grid, kept as given");
}

std::vector<Volume> finished(std::vector<Volume> volumes, const fs::path& path) {
  for (auto& v : volumes) {
    checkGeometry(v, path);
    noteShear(v);
    clampInfinities(v, path);
  }
  return volumes;
}

}  // namespace

std::vector<Volume> readAllVolumes(const fs::path& path, const ReadOptions& given) {
  ReadOptions options = given;
  if (options.maxBytes == 0) options.maxBytes = defaultMaxBytes();
  refuseMissing(path);
  return detail::refuseOutOfMemory(path, [&]() -> std::vector<Volume> {
    const FileFormat format = detectFormat(path);
    // A series is chosen among a DICOM folder's; asked of any other file, it was a mistake.
    if (format != FileFormat::Dicom && format != FileFormat::Unknown && !options.series.empty())
      throw InputError(path, "a series ('" + options.series +
                                 "') can be chosen only in DICOM, and this is a " +
                                 (format == FileFormat::Nifti ? "NIfTI" : "MetaImage") + " file");
    // Likewise the regridding of unevenly spaced slices: a NIfTI or MetaImage is a grid already.
    if (format != FileFormat::Dicom && format != FileFormat::Unknown && options.sliceSpacing > 0)
      throw InputError(path, std::string("a slice spacing for uneven slices applies only to a "
                                         "DICOM series, and this is a ") +
                                 (format == FileFormat::Nifti ? "NIfTI" : "MetaImage") +
                                 " file (a regular grid already)");
    switch (format) {
      case FileFormat::Dicom:
        return finished(detail::readDicom(path, options, true), path);
      case FileFormat::Nifti: {
        std::vector<Volume> v;
        v.push_back(detail::readNifti(path, options));
        return finished(std::move(v), path);
      }
      case FileFormat::MetaImage: {
        std::vector<Volume> v;
        v.push_back(detail::readMetaImage(path, options));
        return finished(std::move(v), path);
      }
      case FileFormat::Unknown:
        break;
    }
    throw InputError(
        path,
        "unknown file type (expected a DICOM file or folder, .nii, .nii.gz, .hdr, .mha or .mhd)");
  });
}

Volume readVolume(const fs::path& path, const ReadOptions& given) {
  ReadOptions options = given;
  if (options.maxBytes == 0) options.maxBytes = defaultMaxBytes();
  if (detectFormat(path) == FileFormat::Dicom) {
    refuseMissing(path);
    auto volumes = detail::refuseOutOfMemory(
        path, [&] { return finished(detail::readDicom(path, options, false), path); });
    return std::move(volumes.front());
  }
  auto volumes = readAllVolumes(path, options);
  return std::move(volumes.front());
}

}  // namespace mvw::io
