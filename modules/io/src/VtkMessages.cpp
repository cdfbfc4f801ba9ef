#include "VtkMessages.h"

#include <mutex>

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

namespace mvw::io::detail {

namespace {

std::mutex gMutex;
std::vector<std::string> gErrors;

std::string stripVtkPrefix(std::string text) {
  // "ERROR: In file.cxx, line 12\nvtkClass (0x55d...): message\n\n" -> "message"; a reader
  // passing on its parser's message nests one such prefix in another, so all of them go.
  for (auto p = text.find("(0x"); p != std::string::npos; p = text.find("(0x")) {
    const auto q = text.find("): ", p);
    if (q == std::string::npos) break;
    text = text.substr(q + 3);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (auto& c : text)
    if (c == '\n') c = ' ';
  return text;
}

class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
  // The raw error text, before VTK's logger decorates it. Warnings and other text are
  // dropped: readers decide from errors alone.
  void DisplayErrorText(const char* text) override {
    std::lock_guard<std::mutex> lock(gMutex);
    gErrors.push_back(stripVtkPrefix(text ? text : ""));
  }
  void DisplayText(const char*) override {}
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
};
vtkStandardNewMacro(CapturingOutputWindow);

void installOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);  // VTK 9 also logs errors to stderr
    vtkSmartPointer<CapturingOutputWindow> window = vtkSmartPointer<CapturingOutputWindow>::New();
    vtkOutputWindow::SetInstance(window);
  });
}

}  // namespace

VtkMessageScope::VtkMessageScope() {
  installOnce();
  std::lock_guard<std::mutex> lock(gMutex);
  gErrors.clear();
}

VtkMessageScope::~VtkMessageScope() = default;

std::vector<std::string> VtkMessageScope::errors() const {
  std::lock_guard<std::mutex> lock(gMutex);
  return gErrors;
}

std::string VtkMessageScope::firstError() const {
  std::lock_guard<std::mutex> lock(gMutex);
  return gErrors.empty() ? std::string() : gErrors.front();
}

}  // namespace mvw::io::detail
