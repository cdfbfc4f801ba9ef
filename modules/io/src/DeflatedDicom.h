#pragma once
// Deflated Explicit VR Little Endian (1.2.840.10008.1.2.1.99): vtk-dicom's parser reads the
// data set as if it were not compressed, so the data set is inflated here into a temporary
// file with the Explicit VR Little Endian transfer syntax, which vtk-dicom then reads.
#include <cstddef>
#include <filesystem>
#include <optional>

namespace mvw::io::detail {

// The inflated copy of a deflated DICOM file; removed when this object goes away.
class InflatedDicom {
 public:
  explicit InflatedDicom(std::filesystem::path path) : path_(std::move(path)) {}
  ~InflatedDicom();
  InflatedDicom(InflatedDicom&& other) noexcept : path_(std::move(other.path_)) {
    other.path_.clear();
  }
  InflatedDicom(const InflatedDicom&) = delete;
  InflatedDicom& operator=(const InflatedDicom&) = delete;
  InflatedDicom& operator=(InflatedDicom&&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// nullopt when `file` is not a Part 10 file with the deflated transfer syntax. Throws
// InputError naming `file` when the meta header or the deflate stream is broken, or when the
// data set inflates to more than maxBytes.
std::optional<InflatedDicom> inflateDeflatedDicom(const std::filesystem::path& file,
                                                  std::size_t maxBytes);

}  // namespace mvw::io::detail
