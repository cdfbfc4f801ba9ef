#include "PacsPanel.h"

#include <algorithm>
#include <cstring>
#include <string>

#include <imgui.h>

#include "mvw/viewer/PanelText.h"

namespace mvw::app {

// The window draws the window-free viewer (mvw::viewer) and acts through it throughout.
using namespace mvw::viewer;

namespace {

using Role = PacsBrowser::Role;

const ImVec4 kError(1.0f, 0.45f, 0.4f, 1.0f);
const ImVec4 kBusy(1.0f, 0.85f, 0.3f, 1.0f);
const ImVec4 kQuiet(0.65f, 0.65f, 0.7f, 1.0f);
const ImVec4 kChosen(0.45f, 0.9f, 1.0f, 1.0f);

// An InputText on a std::string (Debian's libimgui has no imgui_stdlib).
bool inputString(const char* label, std::string& text, const char* hint = nullptr) {
  char buffer[256] = {};
  std::strncpy(buffer, text.c_str(), sizeof buffer - 1);
  const bool changed = hint ? ImGui::InputTextWithHint(label, hint, buffer, sizeof buffer)
                            : ImGui::InputText(label, buffer, sizeof buffer);
  if (changed) text = buffer;
  return changed;
}

// A line in a colour, wrapped at the window's edge (a server's message can be long).
void wrapped(const ImVec4& colour, const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

}  // namespace

void PacsPanel::drawSearch() {
  const auto& servers = browser_.servers();
  ImGui::TextColored(kQuiet, "servers: %s", browser_.serversFile().string().c_str());
  if (!browser_.serversProblem().empty()) wrapped(kError, browser_.serversProblem());
  if (servers.empty()) {
    ImGui::TextWrapped("%s", noServersHelp(browser_.serversFile()).c_str());
    return;
  }
  const int chosen = browser_.server();
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("server");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(260 * scale_);
  if (ImGui::BeginCombo("##server", chosen >= 0 ? servers[std::size_t(chosen)].name.c_str()
                                                : "choose a server")) {
    for (int i = 0; i < static_cast<int>(servers.size()); ++i)
      if (ImGui::Selectable(servers[std::size_t(i)].name.c_str(), i == chosen))
        browser_.selectServer(i);
    ImGui::EndCombo();
  }
  if (chosen < 0) return;
  const PacsServerEntry& server = servers[std::size_t(chosen)];
  ImGui::SameLine();
  ImGui::TextColored(kQuiet, "%s", serverNote(server).c_str());
  // The search keys, each label before its field (read left to right).
  pacs::StudyQuery& q = browser_.query();
  const float label = ImGui::CalcTextSize("patient name ").x;
  const float input = 180 * scale_;
  auto keyField = [&](const char* text, const char* id, std::string& value, const char* hint,
                      bool sameLine) {
    if (sameLine) ImGui::SameLine(0.0f, 24.0f * scale_);
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(text);
    ImGui::SameLine(sameLine ? 0.0f : label + ImGui::GetStyle().WindowPadding.x);
    ImGui::SetNextItemWidth(input);
    inputString(id, value, hint);
  };
  keyField("patient ID", "##patient-id", q.patientId, nullptr, false);
  keyField("patient name", "##patient-name", q.patientName, "Doe* (wildcards * ?)", true);
  // The study date as a range, from and to (either may stay empty: from onwards, up to), kept
  // as the query's DICOM range "FROM-TO" (a script's study-date= shows here the same way).
  auto [from, to] = browser_.studyDateRange();
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("study date");
  ImGui::SameLine(label + ImGui::GetStyle().WindowPadding.x);
  ImGui::SetNextItemWidth(input * 0.5f - 12.0f * scale_);
  bool dateChanged = inputString("##date-from", from, "YYYYMMDD");
  ImGui::SameLine();
  ImGui::TextUnformatted("to");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(input * 0.5f - 12.0f * scale_);
  dateChanged |= inputString("##date-to", to, "YYYYMMDD");
  if (dateChanged) browser_.setStudyDateRange(from, to);
  keyField("modality", "##modality", q.modality, "CT, PT, MR", true);
  ImGui::SameLine(0.0f, 24.0f * scale_);
  ImGui::BeginDisabled(browser_.busy());
  if (ImGui::Button("Search")) browser_.search();
  ImGui::EndDisabled();
}

void PacsPanel::drawStudies() {
  const auto& studies = browser_.studies();
  ImGui::Text("Studies (%zu)", studies.size());
  const float rows = static_cast<float>(std::clamp<std::size_t>(studies.size(), 1, 5));
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingStretchProp;
  if (!ImGui::BeginTable("studies", 6, flags,
                         ImVec2(0, (rows + 1.4f) * ImGui::GetFrameHeightWithSpacing())))
    return;
  ImGui::TableSetupScrollFreeze(0, 1);
  for (const char* c : {"patient", "patient ID", "date", "modalities", "description", "series"})
    ImGui::TableSetupColumn(c);
  ImGui::TableHeadersRow();
  for (int i = 0; i < static_cast<int>(studies.size()); ++i) {
    const std::vector<std::string> row = PacsBrowser::studyRow(studies[std::size_t(i)]);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const std::string label = row[0] + "##study" + std::to_string(i);
    ImGui::BeginDisabled(browser_.busy());
    if (ImGui::Selectable(label.c_str(), i == browser_.study(),
                          ImGuiSelectableFlags_SpanAllColumns))
      browser_.chooseStudy(i);
    ImGui::EndDisabled();
    for (std::size_t column = 1; column < row.size(); ++column) {
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(row[column].c_str());
    }
  }
  ImGui::EndTable();
}

void PacsPanel::drawSeries() {
  const auto& series = browser_.series();
  if (browser_.study() < 0) return;
  ImGui::Text(
      "Series of the study (%zu): choose the anatomical (A), functional (F) and "
      "segmentation (S) series",
      series.size());
  const float rows = static_cast<float>(std::clamp<std::size_t>(series.size(), 1, 6));
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingStretchProp;
  if (!ImGui::BeginTable("series", 7, flags,
                         ImVec2(0, (rows + 1.4f) * ImGui::GetFrameHeightWithSpacing())))
    return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("A", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("F", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("S", ImGuiTableColumnFlags_WidthFixed);
  for (const char* c : {"number", "modality", "description", "images"}) ImGui::TableSetupColumn(c);
  ImGui::TableHeadersRow();
  for (int i = 0; i < static_cast<int>(series.size()); ++i) {
    const pacs::Match& s = series[std::size_t(i)];
    const std::string uid = pacs::matchValue(s, "SeriesInstanceUID");
    ImGui::TableNextRow();
    ImGui::PushID(i);
    for (Role role : {Role::Anatomical, Role::Functional, Role::Segmentation}) {
      ImGui::TableNextColumn();
      bool on = browser_.chosen(role) == uid;
      ImGui::PushID(static_cast<int>(role));
      if (ImGui::Checkbox("##role", &on)) browser_.setSeries(role, on ? uid : std::string());
      ImGui::PopID();
    }
    const bool used = browser_.isChosen(uid);
    for (const std::string& value : PacsBrowser::seriesRow(s)) {
      ImGui::TableNextColumn();
      if (used)
        ImGui::TextColored(kChosen, "%s", value.c_str());
      else
        ImGui::TextUnformatted(value.c_str());
    }
    ImGui::PopID();
  }
  ImGui::EndTable();
}

void PacsPanel::drawOpen() {
  if (browser_.study() < 0) return;
  const pacs::Match& study = browser_.studies()[std::size_t(browser_.study())];
  ImGui::Separator();
  const PacsServerEntry& server = browser_.servers()[std::size_t(browser_.server())];
  ImGui::TextColored(kChosen, "%-13s %s", "server:", server.name.c_str());
  ImGui::TextColored(kChosen, "%-13s %s", "study:", PacsBrowser::describeStudy(study).c_str());
  for (Role role : {Role::Anatomical, Role::Functional, Role::Segmentation})
    ImGui::TextColored(kChosen, "%-13s %s",
                       (std::string(PacsBrowser::roleName(role)) + ":").c_str(),
                       browser_.describeSeries(browser_.chosen(role)).c_str());
  const char* methods[] = {"none (world coordinates)", "rigid (mutual information)",
                           "affine (mutual information)"};
  int method = std::min(static_cast<int>(browser_.registration), 2);
  ImGui::SetNextItemWidth(260 * scale_);
  if (ImGui::Combo("registration", &method, methods, 3))
    browser_.registration = static_cast<config::RegistrationMethod>(method);
  ImGui::SameLine();
  const char* kinds[] = {"pet", "spect", "fmri", "perfusion", "dose", "labels", "other"};
  int kind = static_cast<int>(browser_.functionalKind);  // config::FunctionalKind's order
  ImGui::SetNextItemWidth(120 * scale_);
  if (ImGui::Combo("functional kind", &kind, kinds, 7))
    browser_.functionalKind = static_cast<config::FunctionalKind>(kind);
  ImGui::BeginDisabled(browser_.busy() || browser_.chosen(Role::Anatomical).empty());
  if (ImGui::Button("Open", ImVec2(120 * scale_, 0))) browser_.open();
  ImGui::EndDisabled();
}

void PacsPanel::draw(float left) {
  if (!visible_) return;
  const ImGuiIO& io = ImGui::GetIO();
  const float width = std::min(io.DisplaySize.x - left - 24.0f, 900.0f * scale_);
  ImGui::SetNextWindowPos(ImVec2(left + 12.0f, 16.0f), ImGuiCond_Appearing);
  ImGui::SetNextWindowSize(ImVec2(width, std::min(io.DisplaySize.y - 32.0f, 620.0f * scale_)),
                           ImGuiCond_Appearing);
  ImGui::SetNextWindowBgAlpha(1.0f);  // opaque: the panes under it would blur the text
  ImGui::Begin("Open a study from the PACS", &visible_, ImGuiWindowFlags_NoCollapse);
  drawSearch();
  if (browser_.server() >= 0) {
    ImGui::Separator();
    drawStudies();
    drawSeries();
    drawOpen();
  }
  ImGui::Separator();
  if (browser_.busy()) {
    if (const float f = browser_.progress(); f >= 0.0f) ImGui::ProgressBar(f, ImVec2(-1, 0));
    wrapped(kBusy, browser_.activity());
  } else if (!browser_.error().empty())
    wrapped(kError, std::string(browser_.failedStep()) + " failed: " + browser_.error());
  else if (!browser_.status().empty())
    wrapped(kQuiet, browser_.status());
  ImGui::End();
}

}  // namespace mvw::app
