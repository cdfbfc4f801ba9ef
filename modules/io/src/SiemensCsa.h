#pragma once
// Siemens CSA Image Header Info (0029,xx10, creator "SIEMENS CSA HEADER"), the "SV10" (CSA2)
// layout: written by hand because this vtk-dicom version has no CSA parser. Every length in
// the header is checked against the bytes actually present; nothing is allocated from a
// claimed size, so arbitrary bytes give a reason string, never a crash.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mvw::io::detail {

class CsaHeader {
 public:
  // nullopt (and *why) when the bytes are not a well-formed SV10 header.
  static std::optional<CsaHeader> parse(const std::uint8_t* data, std::size_t size,
                                        std::string* why);

  // The items of element `name` (empty when absent). Items are the stored strings, trimmed.
  const std::vector<std::string>& items(const std::string& name) const;
  // Item `index` of `name` as a finite number, or nullopt.
  std::optional<double> number(const std::string& name, std::size_t index = 0) const;

 private:
  std::map<std::string, std::vector<std::string>> elements_;
};

}  // namespace mvw::io::detail
