#include "mvw/io/VolumeWriter.h"

#include <unistd.h>

#include <string>
#include <system_error>

#include "Formats.h"
#include "mvw/core/Error.h"

namespace mvw::io {

namespace {

namespace fs = std::filesystem;

enum class OutputFormat { Nifti, MetaImage, Unknown };

// The format a file name asks for; Unknown also for the bare extension (".nii.gz" is a hidden
// file with no name).
OutputFormat outputFormat(const fs::path& path) {
  const std::string name = path.filename().string();
  for (const char* ext : {".nii.gz", ".nii", ".mha", ".mhd"}) {
    const std::string e(ext);
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0)
      return e[1] == 'n' ? OutputFormat::Nifti : OutputFormat::MetaImage;
  }
  return OutputFormat::Unknown;
}

}  // namespace

void writeVolume(const Volume& volume, const std::filesystem::path& path) {
  if (volume.empty()) throw Error(path.string() + ": refusing to write an empty volume");
  switch (outputFormat(path)) {
    case OutputFormat::Nifti:
      return detail::writeNifti(volume, path);
    case OutputFormat::MetaImage:
      return detail::writeMetaImage(volume, path);
    case OutputFormat::Unknown:
      break;
  }
  throw InputError(path, "unknown output format (use NAME.nii, .nii.gz, .mha or .mhd)");
}

void checkVolumeOutput(const fs::path& output, const std::vector<fs::path>& inputs) {
  if (outputFormat(output) == OutputFormat::Unknown)
    throw InputError(output, "unknown output format (use NAME.nii, .nii.gz, .mha or .mhd)");
  std::error_code ec;
  if (fs::is_directory(output, ec)) throw InputError(output, "is a folder, not a file name");
  const fs::path parent = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(output, "its folder " + parent.string() + " does not exist");
  if (::access(parent.c_str(), W_OK | X_OK) != 0)
    throw InputError(output, "its folder " + parent.string() + " is not writable");
  // The file is written beside and renamed onto the output's name: that replaces what the
  // name holds (a link there is replaced, not followed). The input is lost when its own path,
  // links resolved, is that name; another hard link to it, or a link at the output's name,
  // leaves it whole.
  const fs::path entry = fs::weakly_canonical(parent, ec) / output.filename();
  for (const fs::path& input : inputs) {
    std::error_code ic;
    const fs::path target = fs::weakly_canonical(input, ic);
    if (!ec && !ic && fs::exists(target, ic) && target == entry)
      throw InputError(output, "is the input " + input.string() +
                                   ": writing it would destroy what is being read (choose "
                                   "another output name)");
  }
}

}  // namespace mvw::io
