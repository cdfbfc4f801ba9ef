// libFuzzer: a QIDO-RS answer's DICOM JSON as webFind reads it (pacs' internal parseQidoAnswer),
// for a series-level query (the study UID is in the request path). ServiceError is the refusal
// of a bad answer; a crash or any other exception is a finding.
#include <cstdint>
#include <string>

#include "FuzzInput.h"
#include "Internal.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string body(reinterpret_cast<const char*>(data), size);
  const mvw::pacs::Match keys = {{"StudyInstanceUID", "1.2.3"}, {"Modality", ""}};
  mvw::fuzz::expectOnly<mvw::ServiceError>([&] {
    const auto matches =
        mvw::pacs::detail::parseQidoAnswer("http://pacs", body, {"StudyInstanceUID"}, keys);
    for (const auto& m : matches)
      if (!m.count("StudyInstanceUID")) mvw::fuzz::finding("qido: a match lost its path UID");
  });
  return 0;
}
