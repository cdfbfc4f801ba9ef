#include "mvw/io/LabelTable.h"

#include <fstream>
#include <limits>
#include <sstream>

#include "FileChecks.h"
#include "mvw/core/Error.h"

namespace mvw::io {

using detail::regularFileSize;

namespace fs = std::filesystem;

std::map<int, std::string> readLabelTable(const fs::path& path) {
  constexpr std::uintmax_t kMaxBytes = 16u << 20;
  if (regularFileSize(path) > kMaxBytes)
    throw InputError(path, "label table larger than 16 MiB: not a label table");
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the label table");
  std::map<int, std::string> out;
  std::map<std::string, int> numberOf;  // names are how glyph views choose labels: one each
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    // Line ends of any system (CR LF, and the CR CR LF of a CR LF file converted once more).
    line.erase(line.find_last_not_of(" \t\r") + 1);
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    long long number = -1;
    std::string name;
    if (!(fields >> number) || !(fields >> name)) {
      std::string shown;
      for (char c : line.substr(0, 80)) shown += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
      throw InputError(path,
                       "line " + std::to_string(n) + " is not \"NUMBER NAME\": '" + shown + "'");
    }
    for (char c : name)
      if (static_cast<unsigned char>(c) < 0x20)
        throw InputError(path, "line " + std::to_string(n) +
                                   ": the name holds a control character (byte " +
                                   std::to_string(static_cast<unsigned char>(c)) + ")");
    if (number < 0 || number > std::numeric_limits<int>::max())
      throw InputError(path, "line " + std::to_string(n) + ": label " + std::to_string(number) +
                                 " is outside 0 .. 2147483647");
    if (!out.emplace(static_cast<int>(number), name).second)
      throw InputError(path, "label " + std::to_string(number) + " is named twice");
    if (const auto [at, fresh] = numberOf.emplace(name, static_cast<int>(number)); !fresh)
      throw InputError(path, "the name '" + name + "' is given to labels " +
                                 std::to_string(at->second) + " and " + std::to_string(number) +
                                 " (a glyph view choosing it by name could not tell which)");
  }
  return out;
}

std::optional<fs::path> labelTableBeside(const fs::path& volume) {
  fs::path stem = volume;
  if (stem.extension() == ".gz") stem.replace_extension();
  std::error_code ec;
  for (fs::path candidate :
       {fs::path(stem.string() + ".txt"), fs::path(stem).replace_extension(".txt")})
    if (fs::is_regular_file(candidate, ec)) return candidate;
  return std::nullopt;
}

}  // namespace mvw::io
