#pragma once
// A JSON file as the batch runner and its report read their own records (done.json,
// failed.json, batch.json, render.json, stats.json): null when it is missing or not JSON (a
// record is written atomically, so a half-written one is never seen; a damaged one counts as
// none).
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

namespace mvw::batch::detail {

inline nlohmann::json readJsonOrNull(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

}  // namespace mvw::batch::detail
