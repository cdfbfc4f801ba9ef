#include "mvw/viewer/PanelText.h"

#include <algorithm>
#include <cmath>

#include "mvw/core/Format.h"

namespace mvw::viewer {

std::string wrapPaneMessage(const std::string& message, float width,
                            const std::function<float(const std::string&)>& textWidth) {
  std::string why, line;
  std::size_t start = 0;
  while (start < message.size()) {
    std::size_t end = message.find(message[start] == '(' ? ')' : ' ', start);
    if (end != std::string::npos && message[start] == '(') end = message.find(' ', end);
    if (end == std::string::npos) end = message.size();
    const std::string word = message.substr(start, end - start);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && textWidth(longer) > width) {
      why += line + "\n";
      line = word;
    } else {
      line = longer;
    }
    if (!line.empty() && line.back() == ';') why += line + "\n", line.clear();
    start = end + 1;
  }
  return why + line;
}

std::vector<std::string> roiStatsLines(const std::string& volume, const study::RoiStats& s) {
  const std::string u = s.unit.empty() ? "" : " " + s.unit;
  std::vector<std::string> lines{"  " + volume + ": " + std::to_string(s.voxels) + " voxels, " +
                                 shortNumber(s.volumeMl, 3) + " ml"};
  if (s.voxels == 0) return lines;
  lines.push_back("    max " + shortNumber(s.max, 4) + "  mean " + shortNumber(s.mean, 4) +
                  "  SD " + shortNumber(s.sd, 4) + u);
  if (s.peak) lines.push_back("    SUVpeak " + shortNumber(*s.peak, 4) + u + " (1 cm3)");
  return lines;
}

std::string sphereLabel(std::size_t index, bool saved, double radiusMm) {
  return (saved ? "ROI " + std::to_string(index + 1) + "  " : std::string()) + "r " +
         fixedNumber(radiusMm, 1) + " mm";
}

std::string glyphLegendLine(const render::GlyphLegendEntry& e) {
  return e.label + "  " +
         (e.size <= 0
              ? "no glyph"
              : std::to_string(int(std::lround(100 * e.size))) + " % " + glyphKindName(e.kind));
}

std::vector<std::pair<int, std::string>> glyphPickerLabels(const std::map<int, std::string>& names,
                                                           double functionalTop) {
  std::vector<std::pair<int, std::string>> labels;
  for (const auto& [n, name] : names)
    if (n > 0) labels.emplace_back(n, name);
  if (labels.empty()) {
    const int top = std::clamp(int(functionalTop), 0, 255);
    for (int n = 1; n <= top; ++n) labels.emplace_back(n, "");
  }
  return labels;
}

std::string glyphPickerHeader(std::size_t chosen) {
  return "glyph labels (" +
         (chosen == 0 ? std::string("all above the window") : std::to_string(chosen) + " chosen") +
         ")###glyph-labels";
}

std::string sphereHeader(std::size_t index, const config::SphereMeasurement& s) {
  return "ROI " + std::to_string(index + 1) + ": r " + fixedNumber(s.radiusMm, 1) + " mm at " +
         fixedNumber(s.centre[0], 1) + ", " + fixedNumber(s.centre[1], 1) + ", " +
         fixedNumber(s.centre[2], 1);
}

std::string rulerLine(std::size_t index, double lengthMm) {
  return "ruler " + std::to_string(index + 1) + ": " + fixedNumber(lengthMm, 1) + " mm";
}

std::string registrationLine(const std::string& description) {
  return "registration: " + (description == "none" ? "none (world coordinates)" : description);
}

std::string rerunRegistrationLabel(const std::string& method) {
  return "re-run registration (" + method + " MI)";
}

std::string viewerTitle(const std::string& studyName) {
  return "mvw view" + (studyName.empty() ? "" : ": " + studyName);
}

std::string serverNote(const config::SavedServer& server) {
  return server.url +
         (server.url.rfind("dicom://", 0) == 0 ? "  (calling AE " + server.callingAet + ")" : "");
}

std::string noServersHelp(const std::filesystem::path& serversFile) {
  return "No server: list them in " + serversFile.string() +
         " as {\"servers\": [{\"name\": \"Clinic PACS\", \"url\": \"dicom://PACS@host:104\", "
         "\"calling_aet\": \"MVW\"}]} (or mvw view --servers FILE).";
}

}  // namespace mvw::viewer
