#pragma once
// VTK reports problems through vtkOutputWindow, as text on stderr. Inside mvw every VTK
// message is captured instead, so a reader can turn it into one InputError naming the file.
#include <string>
#include <vector>

namespace mvw::io::detail {

class VtkMessageScope {
 public:
  VtkMessageScope();  // installs the capturing output window once; starts a fresh record
  ~VtkMessageScope();
  VtkMessageScope(const VtkMessageScope&) = delete;
  VtkMessageScope& operator=(const VtkMessageScope&) = delete;

  std::vector<std::string> errors() const;
  std::string firstError() const;  // "" if none; the text after VTK's "Class (0x...): " prefix
};

}  // namespace mvw::io::detail
