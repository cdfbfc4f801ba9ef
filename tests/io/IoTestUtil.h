#pragma once
// For the io tests on synthetic volumes (slice placement, mosaics, values on read): the notes a
// reader leaves on what it changed.
#include <string>

#include "mvw/core/Volume.h"

namespace mvw::test {

// Whether one of the volume's notes contains `part`.
inline bool hasNote(const mvw::Volume& v, const std::string& part) {
  for (const auto& n : v.metadata().notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace mvw::test
