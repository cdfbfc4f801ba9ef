#include "mvw/io/VolumeWriter.h"

#include <string>

#include "Formats.h"
#include "mvw/core/Error.h"

namespace mvw::io {

void writeVolume(const Volume& volume, const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  auto ends = [&](const std::string& s) {
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  if (volume.empty()) throw Error(path.string() + ": refusing to write an empty volume");
  if (ends(".nii") || ends(".nii.gz")) return detail::writeNifti(volume, path);
  if (ends(".mha") || ends(".mhd")) return detail::writeMetaImage(volume, path);
  throw InputError(path, "unknown output format (use .nii, .nii.gz, .mha or .mhd)");
}

}  // namespace mvw::io
