#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <new>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mvw::io::detail {

// Size of a regular file; throws InputError if it is missing or not a regular file.
std::uintmax_t regularFileSize(const std::filesystem::path& path);

// Throws the InputError of a file whose reading ran out of memory: a length field that made a
// library (vtk-dicom's parser, a decoder) allocate more than the machine holds.
[[noreturn]] void throwOutOfMemory(const std::filesystem::path& file);

// Runs `read`, the reading of `file`, with a std::bad_alloc from it turned into the file's
// InputError (throwOutOfMemory): bad input, not an internal fault.
template <class F>
auto refuseOutOfMemory(const std::filesystem::path& file, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const std::bad_alloc&) {
    throwOutOfMemory(file);
  }
}

// Size of the data file a header points to; a missing one is reported against the header.
std::uintmax_t companionFileSize(const std::filesystem::path& header,
                                 const std::filesystem::path& data);

// dims.x*dims.y*dims.z*components*bytesPerValue with overflow and limit checks: throws
// InputError naming `file` when any factor is not positive or the product exceeds maxBytes.
std::size_t checkedVolumeBytes(const std::filesystem::path& file, glm::ivec3 dims,
                               long long components, std::size_t bytesPerValue,
                               std::size_t maxBytes);

// What keeps an index-to-world matrix from being a geometry: an entry of its axes or origin
// that is not finite, or axes that are not independent (|det| at most 1e-6 of the product of
// their lengths). The NIfTI reader asks it of the sform and qform before choosing one; every
// reader's volume is asked it again (VolumeReader).
enum class GeometryProblem { None, NotFinite, Singular };
GeometryProblem geometryProblem(const glm::dmat4& worldFromIndex);

}  // namespace mvw::io::detail
