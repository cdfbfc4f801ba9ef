#pragma once
// Every file mvw writes appears whole or not at all. This is the rule's home for one file
// (volumes, PNGs, study configs, transforms, reports): it is written under a temporary name in
// the same folder and renamed onto its own. Its home for a group of files or a folder (a
// command's outputs that appear together) is StagedFolder.h.
#include <filesystem>
#include <functional>
#include <string_view>

namespace mvw::io {

// Writes through `write(tmpPath)` then renames onto `path`; removes the temporary on failure.
// The temporary keeps the real extension(s), so extension-driven writers (.nii.gz) still work.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write);

// `text` as the whole content of `path`; throws mvw::Error naming the file if it cannot.
void writeTextAtomically(const std::filesystem::path& path, std::string_view text);

// A copy of `from` as `to`, replacing it.
void copyFileAtomically(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace mvw::io
