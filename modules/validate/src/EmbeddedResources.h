#pragma once
#include <map>
#include <string_view>

namespace mvw::validate::detail {

// Every file of modules/validate/resources/ (the report's HTML template), keyed by its name
// (generated at build time by cmake/EmbedFiles.cmake).
const std::map<std::string_view, std::string_view>& embeddedResources();

}  // namespace mvw::validate::detail
