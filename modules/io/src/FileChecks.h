#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mvw::io::detail {

// Size of a regular file; throws InputError if it is missing or not a regular file.
std::uintmax_t regularFileSize(const std::filesystem::path& path);

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
