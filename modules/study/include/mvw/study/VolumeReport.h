#pragma once
// What `mvw info` says about volumes, as text for a person and as JSON for a script: each
// volume's file, format, series, geometry, value range, unit and the reader's notes, and for a
// study config the role each volume has in the study. Here rather than in io because a study
// config names the roles, and io stays free of the config and of JSON.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::study {

// A series number as every JSON report writes it (`mvw info --json`, `mvw convert`'s sidecar):
// the number, or null for a series without one (SeriesNumber is optional in DICOM, and 0 is a
// number a series may have; VolumeMetadata keeps -1 for none).
nlohmann::json seriesNumberJson(int seriesNumber);

// One volume's report ("path", "format", "dimensions", ..., "notes"; `mvw convert`'s sidecar
// starts from it).
nlohmann::json volumeJson(const Volume& volume);
// One volume's report as lines of text, the first its file's path, the others indented.
void printVolume(std::ostream& out, const Volume& volume);

struct ReportedVolume {
  std::string role;  // "anatomical", "functional (pet)" for a study config's; "" for a file's
  Volume volume;
};

// Every volume `paths` name, all read before any is reported (a bad input anywhere means no
// partial report): a study config's (.json) anatomical and functional volumes, with their
// roles, and every volume of each other path (io::readAllVolumes: every series of a folder
// when `options` chooses none). A config's PACS sources are read with `pacs`.
std::vector<ReportedVolume> readReportedVolumes(const std::vector<std::filesystem::path>& paths,
                                                const io::ReadOptions& options,
                                                const pacs::Options& pacs);

// The volumes as a JSON array of volumeJson objects, each with its "role" where it has one.
nlohmann::json volumesJson(const std::vector<ReportedVolume>& volumes);
// The volumes as printVolume's text, a blank line between two, each after its "[role] ".
void printVolumes(std::ostream& out, const std::vector<ReportedVolume>& volumes);

}  // namespace mvw::study
