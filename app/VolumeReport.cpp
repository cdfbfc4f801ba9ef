#include "VolumeReport.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "mvw/core/Orientation.h"

namespace mvw::app {

namespace {

std::string fmt(double v, int decimals = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string fmtValue(double v) {
  // Integer-valued ranges print without decimals (HU, labels); others with 4 significant digits.
  if (std::abs(v) < 1e9 && v == std::floor(v)) return fmt(v, 0);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

nlohmann::json volumeJson(const Volume& volume) {
  const auto& md = volume.metadata();
  const glm::ivec3 d = volume.dimensions();
  const glm::dvec3 s = volume.spacing(), o = volume.origin();
  const glm::dmat3 dir = volume.direction();
  const auto [lo, hi] = volume.valueRange();
  nlohmann::json j;
  j["path"] = md.sourcePath;
  j["format"] = md.format;
  j["modality"] = md.modality;
  j["dimensions"] = {d.x, d.y, d.z};
  j["components"] = volume.components();
  j["scalar_type"] = std::string(scalarName(volume.scalarType()));
  j["spacing_mm"] = {s.x, s.y, s.z};
  j["origin_lps_mm"] = {o.x, o.y, o.z};
  j["orientation"] = orientationCode(dir);
  j["oblique"] = isOblique(dir);
  // Rows of the 3x3 direction matrix; column c is the world (LPS) direction of index axis c.
  j["direction"] = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) j["direction"].push_back({dir[0][r], dir[1][r], dir[2][r]});
  j["value_range"] = {lo, hi};
  j["unit"] = md.unit;
  if (md.format == "DICOM") {
    j["series_instance_uid"] = md.seriesInstanceUid;
    j["series_description"] = md.seriesDescription;
    j["series_number"] = md.seriesNumber;
  }
  if (md.sliceSpacing) {
    const auto& ss = *md.sliceSpacing;
    j["slice_spacing"] = {{"slices", ss.slices},   {"nominal_mm", ss.nominal},
                          {"min_mm", ss.minimum},  {"max_mm", ss.maximum},
                          {"regular", ss.regular}, {"resampled", ss.resampled}};
  }
  j["notes"] = md.notes;
  return j;
}

void printVolume(std::ostream& out, const Volume& volume) {
  const auto& md = volume.metadata();
  const glm::ivec3 d = volume.dimensions();
  const glm::dvec3 s = volume.spacing(), o = volume.origin();
  const glm::dmat3 dir = volume.direction();
  const auto [lo, hi] = volume.valueRange();
  out << md.sourcePath << "\n";
  out << "  format       " << md.format << "\n";
  if (md.format == "DICOM")
    out << "  series       #" << md.seriesNumber << " \"" << md.seriesDescription << "\"\n"
        << "  series UID   " << md.seriesInstanceUid << "\n";
  else if (!md.seriesDescription.empty())
    out << "  description  \"" << md.seriesDescription << "\"\n";
  out << "  modality     " << (md.modality.empty() ? "(not stated)" : md.modality) << "\n";
  out << "  dimensions   " << d.x << " x " << d.y << " x " << d.z;
  if (volume.components() > 1) out << " x " << volume.components() << " components";
  out << "  (" << scalarName(volume.scalarType()) << ")\n";
  out << "  spacing      " << fmt(s.x, 4) << " x " << fmt(s.y, 4) << " x " << fmt(s.z, 4)
      << " mm\n";
  out << "  origin       " << fmt(o.x) << ", " << fmt(o.y) << ", " << fmt(o.z) << " mm (LPS)\n";
  out << "  orientation  " << orientationCode(dir) << (isOblique(dir) ? " (oblique)" : "") << "\n";
  out << "  direction    ";
  for (int r = 0; r < 3; ++r) {
    out << (r ? "               " : "") << "[";
    for (int c = 0; c < 3; ++c) out << (c ? " " : "") << fmt(dir[c][r], 4);
    out << "]\n";
  }
  out << "  value range  " << fmtValue(lo) << " .. " << fmtValue(hi)
      << (md.unit.empty() ? "" : " " + md.unit) << "\n";
  if (md.sliceSpacing) {
    const auto& ss = *md.sliceSpacing;
    out << "  slices       " << ss.slices << ", spacing " << fmt(ss.nominal) << " mm, "
        << (ss.regular ? "regular"
                       : "IRREGULAR (" + fmt(ss.minimum) + " .. " + fmt(ss.maximum) + " mm)")
        << (ss.resampled ? ", resampled onto a regular grid" : "") << "\n";
  }
  for (const auto& note : md.notes) out << "  note         " << note << "\n";
}

}  // namespace mvw::app
