// libFuzzer: the study-config parser. The scratch folder holds "a.nii" and "dicom/" so that
// configs naming them get past the file checks into the rest of the validation.
#include "FuzzInput.h"
#include "mvw/config/StudyConfig.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool ready = [] {
    std::ofstream(mvw::fuzz::scratch() / "a.nii") << "";
    std::filesystem::create_directories(mvw::fuzz::scratch() / "dicom");
    return true;
  }();
  (void)ready;
  const auto path = mvw::fuzz::writeInput(data, size, "study.json");
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::config::loadStudyConfig(path); });
  return 0;
}
