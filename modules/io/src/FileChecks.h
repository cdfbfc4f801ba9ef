#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>

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

}  // namespace mvw::io::detail
