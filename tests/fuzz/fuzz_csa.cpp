// libFuzzer: the Siemens CSA (SV10) header parser and mosaic unpacking behind it (io's
// internal SiemensCsa / SiemensMosaic): arbitrary bytes as the CSA element of a 64 x 64 mosaic.
#include <cstdint>
#include <string>

#include "SiemensCsa.h"
#include "SiemensMosaic.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string why;
  if (const auto header = mvw::io::detail::CsaHeader::parse(data, size, &why)) {
    (void)header->number("NumberOfImagesInMosaic");
    (void)header->items("SliceNormalVector");
  }
  glm::dmat4 w(1.0);
  mvw::Volume mosaic({64, 64, 1}, 1, mvw::ScalarType::Int16, w);
  (void)mvw::io::detail::unpackMosaic(std::move(mosaic), data, size, 6.0, 5.0);
  return 0;
}
