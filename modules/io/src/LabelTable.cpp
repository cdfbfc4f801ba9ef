#include "mvw/io/LabelTable.h"

#include <fstream>
#include <iterator>
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
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the label table");
  // Lines end in LF, CR LF, CR alone (old Mac) or CR CR LF (CR LF converted once more): CRs
  // before an LF are dropped, a lone CR ends a line.
  const std::string raw{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::string text;
  text.reserve(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '\r') {
      text += raw[i];
      continue;
    }
    std::size_t j = i;
    while (j < raw.size() && raw[j] == '\r') ++j;
    if (j == raw.size() || raw[j] != '\n') text += '\n';
    i = j - 1;
  }
  std::istringstream lines(text);
  auto control = [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; };
  std::map<int, std::string> out;
  std::string line;
  for (int n = 1; std::getline(lines, line); ++n) {
    line.erase(line.find_last_not_of(" \t") + 1);
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    long long number = -1;
    std::string name;
    if (!(fields >> number) || !(fields >> name)) {
      std::string shown;
      for (char c : line.substr(0, 80)) shown += control(c) ? '?' : c;
      throw InputError(path,
                       "line " + std::to_string(n) + " is not \"NUMBER NAME\": '" + shown + "'");
    }
    for (char c : name)
      if (control(c))
        throw InputError(path, "line " + std::to_string(n) +
                                   ": the name holds a control character (byte " +
                                   std::to_string(static_cast<unsigned char>(c)) + ")");
    if (number < 0 || number > std::numeric_limits<int>::max())
      throw InputError(path, "line " + std::to_string(n) + ": label " + std::to_string(number) +
                                 " is outside 0 .. 2147483647");
    if (!out.emplace(static_cast<int>(number), name).second)
      throw InputError(path, "label " + std::to_string(number) + " is named twice");
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
