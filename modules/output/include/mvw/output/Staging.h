#pragma once
// Where a study's views wait until every one of them is written, and what is known about the
// output folder before anything renders.
#include <filesystem>

namespace mvw::output {

// Everything about the output folder that can be known before rendering is said then, so a
// name the file system cannot take costs no render and creates nothing: the nearest folder
// that exists must be a writable folder, and each folder still to be made a name it can hold.
// Throws InputError naming outDir.
void checkOutputFolder(const std::filesystem::path& outDir);

// Orbit frames and movies are written into a staging folder near the output folder while they are
// rendered, and moved into place with everything else once every view has rendered, so a
// failure leaves no partial output. Removed with whatever is left in it.
class Staging {
 public:
  explicit Staging(const std::filesystem::path& outDir);
  ~Staging();
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  // The folder, made on first use.
  const std::filesystem::path& dir();

 private:
  std::filesystem::path dir_;
  bool made_ = false;
};

}  // namespace mvw::output
