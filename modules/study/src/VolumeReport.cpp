#include "mvw/study/VolumeReport.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Format.h"
#include "mvw/core/Orientation.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::study {

namespace {

// Integer-valued ranges print without decimals (HU, labels); others with 4 significant digits.
std::string valueText(double v) {
  if (std::abs(v) < 1e9 && v == std::floor(v)) return fixedNumber(v, 0);
  return shortNumber(v, 4);
}

}  // namespace

nlohmann::json seriesNumberJson(int seriesNumber) {
  return seriesNumber < 0 ? nlohmann::json() : nlohmann::json(seriesNumber);
}

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
    j["series_number"] = seriesNumberJson(md.seriesNumber);
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
    out << "  series       "
        << (md.seriesNumber < 0 ? "(no number)" : "#" + std::to_string(md.seriesNumber)) << " \""
        << md.seriesDescription << "\"\n"
        << "  series UID   " << md.seriesInstanceUid << "\n";
  else if (!md.seriesDescription.empty())
    out << "  description  \"" << md.seriesDescription << "\"\n";
  out << "  modality     " << (md.modality.empty() ? "(not stated)" : md.modality) << "\n";
  out << "  dimensions   " << d.x << " x " << d.y << " x " << d.z;
  if (volume.components() > 1) out << " x " << volume.components() << " components";
  out << "  (" << scalarName(volume.scalarType()) << ")\n";
  out << "  spacing      " << fixedNumber(s.x, 4) << " x " << fixedNumber(s.y, 4) << " x "
      << fixedNumber(s.z, 4) << " mm\n";
  out << "  origin       " << fixedNumber(o.x, 3) << ", " << fixedNumber(o.y, 3) << ", "
      << fixedNumber(o.z, 3) << " mm (LPS)\n";
  out << "  orientation  " << orientationCode(dir) << (isOblique(dir) ? " (oblique)" : "") << "\n";
  out << "  direction    ";
  for (int r = 0; r < 3; ++r) {
    out << (r ? "               " : "") << "[";
    for (int c = 0; c < 3; ++c) out << (c ? " " : "") << fixedNumber(dir[c][r], 4);
    out << "]\n";
  }
  out << "  value range  " << valueText(lo) << " .. " << valueText(hi)
      << (md.unit.empty() ? "" : " " + md.unit) << "\n";
  if (md.sliceSpacing) {
    const auto& ss = *md.sliceSpacing;
    out << "  slices       " << ss.slices << ", spacing " << fixedNumber(ss.nominal, 3) << " mm, "
        << (ss.regular ? "regular"
                       : "IRREGULAR (" + fixedNumber(ss.minimum, 3) + " .. " +
                             fixedNumber(ss.maximum, 3) + " mm)")
        << (ss.resampled ? ", resampled onto a regular grid" : "") << "\n";
  }
  for (const auto& note : md.notes) out << "  note         " << note << "\n";
}

std::vector<ReportedVolume> readReportedVolumes(const std::vector<std::filesystem::path>& paths,
                                                const io::ReadOptions& options,
                                                const pacs::Options& pacs) {
  std::vector<ReportedVolume> volumes;
  for (const auto& p : paths) {
    if (isStudyConfig(p)) {
      const auto study = config::loadStudyConfig(p);
      volumes.push_back({"anatomical", readSource(study.anatomical, options, pacs)});
      if (study.functional)
        volumes.push_back({"functional (" + config::toString(study.functionalKind) + ")",
                           readSource(*study.functional, options, pacs)});
    } else {
      for (auto& v : io::readAllVolumes(p, options)) volumes.push_back({"", std::move(v)});
    }
  }
  return volumes;
}

nlohmann::json volumesJson(const std::vector<ReportedVolume>& volumes) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& v : volumes) {
    auto j = volumeJson(v.volume);
    if (!v.role.empty()) j["role"] = v.role;
    out.push_back(j);
  }
  return out;
}

void printVolumes(std::ostream& out, const std::vector<ReportedVolume>& volumes) {
  for (std::size_t i = 0; i < volumes.size(); ++i) {
    if (i) out << "\n";
    if (!volumes[i].role.empty()) out << "[" << volumes[i].role << "] ";
    printVolume(out, volumes[i].volume);
  }
}

}  // namespace mvw::study
