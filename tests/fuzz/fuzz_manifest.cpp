// libFuzzer: a batch manifest (batch::loadBatchManifest), CSV or JSON: written as manifest.json
// when its first non-blank byte opens a JSON object or array, else as manifest.csv. The scratch
// folder holds "study.json" so that rows naming it get past the file check.
#include <cctype>

#include "FuzzInput.h"
#include "mvw/batch/BatchManifest.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool ready = [] {
    std::ofstream(mvw::fuzz::scratch() / "study.json") << "{}";
    return true;
  }();
  (void)ready;
  std::size_t i = 0;
  while (i < size && std::isspace(data[i])) ++i;
  const bool json = i < size && (data[i] == '{' || data[i] == '[');
  const auto path = mvw::fuzz::writeInput(data, size, json ? "manifest.json" : "manifest.csv");
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::batch::loadBatchManifest(path); });
  return 0;
}
