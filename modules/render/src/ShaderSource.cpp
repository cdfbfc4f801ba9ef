#include "mvw/render/ShaderSource.h"

#include <regex>
#include <set>
#include <sstream>

#include "EmbeddedShaders.h"
#include "mvw/core/Error.h"

namespace mvw::render {

namespace {

void append(std::string_view path, ResolvedShader& out, std::set<std::string>& seen) {
  const int index = static_cast<int>(out.files.size());
  out.files.emplace_back(path);
  seen.insert(std::string(path));
  out.text += "#line 1 " + std::to_string(index) + "\n";
  std::istringstream lines{std::string(shaderFile(path))};
  std::string line;
  static const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  for (int n = 1; std::getline(lines, line); ++n) {
    std::smatch m;
    if (!std::regex_match(line, m, include)) {
      out.text += line + "\n";
      continue;
    }
    const std::string child = m[1];
    if (!detail::embeddedShaders().count(child))
      throw Error("shaders/" + std::string(path) + ":" + std::to_string(n) +
                  ": cannot find include \"" + child + "\"");
    if (!seen.count(child)) append(child, out, seen);
    out.text += "#line " + std::to_string(n + 1) + " " + std::to_string(index) + "\n";
  }
}

}  // namespace

std::string_view shaderFile(std::string_view path) {
  const auto& files = detail::embeddedShaders();
  auto it = files.find(path);
  if (it == files.end())
    throw Error("no shader file shaders/" + std::string(path) + " in this build");
  return it->second;
}

ResolvedShader resolveShader(std::string_view path, const std::vector<std::string>& defines,
                             const std::vector<std::string>& includes) {
  ResolvedShader out;
  out.text = "#version 450 core\n";
  for (const auto& d : defines) out.text += "#define " + d + "\n";
  std::set<std::string> seen;
  for (const auto& include : includes)
    if (!seen.count(include)) append(include, out, seen);
  append(path, out, seen);
  return out;
}

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex location(R"((\d+):(\d+)\((\d+)\)|(\d+)\((\d+)\))");
  std::string out;
  auto begin = log.cbegin();
  std::smatch m;
  while (std::regex_search(begin, log.cend(), m, location)) {
    out.append(begin, m[0].first);
    const bool mesa = m[1].matched;
    const std::size_t file = std::stoul(mesa ? m[1].str() : m[4].str());
    if (file < files.size())
      out += "shaders/" + files[file] + ":" + (mesa ? m[2].str() + ":" + m[3].str() : m[5].str());
    else
      out += m[0].str();
    begin = m[0].second;
  }
  out.append(begin, log.cend());
  return out;
}

}  // namespace mvw::render
