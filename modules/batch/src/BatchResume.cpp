#include "mvw/batch/BatchResume.h"

#include "JsonFile.h"

namespace mvw::batch {

StudyAction decideStudy(const nlohmann::json& done, const BatchStudy& study,
                        const std::map<std::string, std::string>& inputs) {
  if (done.is_object() && done.value("manifest_line", "") == study.line &&
      done.contains("inputs") && done["inputs"] == nlohmann::json(inputs))
    return StudyAction::kSkip;
  return StudyAction::kRun;
}

StudyAction decideStudy(const std::filesystem::path& studyFolder, const BatchStudy& study,
                        const std::map<std::string, std::string>& inputs) {
  return decideStudy(detail::readJsonOrNull(studyFolder / "done.json"), study, inputs);
}

}  // namespace mvw::batch
