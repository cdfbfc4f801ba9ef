#pragma once
// The names of an atlas's labels: one "NUMBER NAME [anything]" per line, as MRIcron ships
// beside its atlases (aal.nii.txt for aal.nii.gz) and FSL-style lookup text; lines starting
// with '#' and blank lines are skipped.
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace mvw::io {

// number -> name. Throws InputError naming the file for a line that is not "NUMBER NAME", a
// number outside 0 .. 2^31-1, a number given twice, or a file over 16 MiB.
std::map<int, std::string> readLabelTable(const std::filesystem::path& path);

// The label table beside a label volume X.nii.gz, X.nii, X.mha: X.nii.txt, then X.txt; none
// when neither exists.
std::optional<std::filesystem::path> labelTableBeside(const std::filesystem::path& volume);

}  // namespace mvw::io
