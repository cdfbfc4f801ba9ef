#pragma once
// The skip-or-rerun decision that makes `mvw batch run` resumable: a study is skipped only when
// OUT/<id>/done.json exists and records the same manifest line and the same input checksums
// (BatchInputs) as now. A failed study (failed.json), a study never run or killed (no
// done.json), a changed line or a changed input byte runs again.
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "mvw/batch/BatchManifest.h"

namespace mvw::batch {

enum class StudyAction { kRun, kSkip };

// From a done.json as read (null when it is missing or damaged).
StudyAction decideStudy(const nlohmann::json& doneRecord, const BatchStudy& study,
                        const std::map<std::string, std::string>& inputs);

// From the study's published folder, OUT/<id>.
StudyAction decideStudy(const std::filesystem::path& studyFolder, const BatchStudy& study,
                        const std::map<std::string, std::string>& inputs);

}  // namespace mvw::batch
