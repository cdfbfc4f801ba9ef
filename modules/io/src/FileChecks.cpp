#include "FileChecks.h"

#include <cmath>
#include <limits>
#include <string>
#include <system_error>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "mvw/core/Error.h"

namespace mvw::io::detail {

std::uintmax_t regularFileSize(const std::filesystem::path& path) {
  requireReadable(path);
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, "not a regular file (a device or a pipe)");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, "cannot read the file size: " + ec.message());
  return size;
}

void throwOutOfMemory(const std::filesystem::path& file) {
  throw InputError(
      file,
      "not enough memory to read this file (a length field claims more than the machine holds)");
}

std::uintmax_t companionFileSize(const std::filesystem::path& header,
                                 const std::filesystem::path& data) {
  std::error_code ec;
  if (!std::filesystem::exists(data, ec))
    throw InputError(header, "its data file " + data.string() + " is missing");
  if (!std::filesystem::is_regular_file(data, ec))
    throw InputError(
        header, "its data file " + data.string() + " is not a regular file (a folder or a device)");
  return regularFileSize(data);
}

std::size_t checkedVolumeBytes(const std::filesystem::path& file, glm::ivec3 dims,
                               long long components, std::size_t bytesPerValue,
                               std::size_t maxBytes) {
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0 || components <= 0)
    throw InputError(file, "header gives non-positive dimensions " + std::to_string(dims.x) +
                               " x " + std::to_string(dims.y) + " x " + std::to_string(dims.z) +
                               " x " + std::to_string(components));
  unsigned long long bytes = bytesPerValue;
  bool overflow = false;
  for (unsigned long long factor :
       {static_cast<unsigned long long>(dims.x), static_cast<unsigned long long>(dims.y),
        static_cast<unsigned long long>(dims.z), static_cast<unsigned long long>(components)})
    overflow |= __builtin_mul_overflow(bytes, factor, &bytes);
  if (overflow || bytes > maxBytes)
    throw InputError(
        file, "header claims " + std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x " +
                  std::to_string(dims.z) + " x " + std::to_string(components) + " values (" +
                  (overflow ? std::string("more than 2^64 bytes")
                            : std::to_string(bytes >> 20) + " MiB") +
                  "), more than the limit of " + std::to_string(maxBytes >> 20) + " MiB");
  return static_cast<std::size_t>(bytes);
}

GeometryProblem geometryProblem(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(m[c][r])) return GeometryProblem::NotFinite;
  const glm::dmat3 a(m);
  const double lengths = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  return lengths > 0 && std::abs(glm::determinant(a)) > 1e-6 * lengths ? GeometryProblem::None
                                                                       : GeometryProblem::Singular;
}

}  // namespace mvw::io::detail
