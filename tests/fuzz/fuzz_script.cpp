// libFuzzer: a viewer script (`mvw view --script`), parsed only: viewer::ViewerScript::parse,
// no window, no study, nothing run.
#include <string>

#include "FuzzInput.h"
#include "mvw/viewer/ViewerScript.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mvw::fuzz::expectInputErrorOnly(
      [&] { (void)mvw::viewer::ViewerScript::parse(text, "script.txt"); });
  return 0;
}
