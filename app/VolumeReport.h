#pragma once
// What `mvw info` says about a volume, as text for a person and as JSON for a script.
#include <ostream>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/Volume.h"

namespace mvw::app {

nlohmann::json volumeJson(const Volume& volume);
void printVolume(std::ostream& out, const Volume& volume);

}  // namespace mvw::app
