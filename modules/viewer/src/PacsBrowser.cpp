#include "mvw/viewer/PacsBrowser.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <fstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

namespace mvw::viewer {

namespace {

using nlohmann::json;

// A DICOM person name as people read it: "Doe^John" -> "Doe, John".
std::string personName(std::string name) {
  if (const auto caret = name.find('^'); caret != std::string::npos) {
    std::string rest = name.substr(caret + 1);
    std::replace(rest.begin(), rest.end(), '^', ' ');
    while (!rest.empty() && rest.back() == ' ') rest.pop_back();
    name = name.substr(0, caret) + (rest.empty() ? "" : ", " + rest);
  }
  return name;
}

}  // namespace

std::string PacsBrowser::dicomDate(const std::string& d) {
  if (d.size() != 8 || d.find_first_not_of("0123456789") != std::string::npos) return d;
  return d.substr(0, 4) + "-" + d.substr(4, 2) + "-" + d.substr(6, 2);
}

std::vector<std::string> PacsBrowser::studyRow(const pacs::Match& s) {
  std::string name = pacs::matchValue(s, "PatientName");
  std::replace(name.begin(), name.end(), '^', ' ');
  return {name.empty() ? "(no name)" : name,
          pacs::matchValue(s, "PatientID"),
          dicomDate(pacs::matchValue(s, "StudyDate")),
          pacs::matchValue(s, "ModalitiesInStudy"),
          pacs::matchValue(s, "StudyDescription"),
          pacs::matchValue(s, "NumberOfStudyRelatedSeries")};
}

std::vector<std::string> PacsBrowser::seriesRow(const pacs::Match& s) {
  std::vector<std::string> row;
  for (const char* key :
       {"SeriesNumber", "Modality", "SeriesDescription", "NumberOfSeriesRelatedInstances"})
    row.push_back(pacs::matchValue(s, key));
  return row;
}

bool PacsBrowser::isChosen(const std::string& uid) const {
  return chosen(Role::Anatomical) == uid || chosen(Role::Functional) == uid ||
         chosen(Role::Segmentation) == uid;
}

std::pair<std::string, std::string> PacsBrowser::studyDateRange() const {
  const std::string& range = query_.studyDate;
  const auto dash = range.find('-');
  return {range.substr(0, dash),
          dash == std::string::npos ? std::string() : range.substr(dash + 1)};
}

void PacsBrowser::setStudyDateRange(const std::string& from, const std::string& to) {
  query_.studyDate = to.empty() && from.empty() ? "" : from + "-" + to;
}

const char* PacsBrowser::roleName(Role role) {
  switch (role) {
    case Role::Anatomical:
      return "anatomical";
    case Role::Functional:
      return "functional";
    case Role::Segmentation:
      break;
  }
  return "segmentation";
}

PacsBrowser::PacsBrowser(pacs::Options options) : options_(std::move(options)) {}

PacsBrowser::~PacsBrowser() = default;  // thread_ (declared last) joins first

void PacsBrowser::setServers(std::vector<PacsServerEntry> servers, std::filesystem::path file,
                             std::string problem) {
  servers_ = std::move(servers);
  serversFile_ = std::move(file);
  serversProblem_ = std::move(problem);
  server_ = -1;
  if (servers_.size() == 1) selectServer(0);
}

void PacsBrowser::selectServer(int index) {
  if (running_ || index == server_) return;
  server_ = index >= 0 && index < static_cast<int>(servers_.size()) ? index : -1;
  studies_.clear();
  series_.clear();
  study_ = -1;
  for (std::string& c : chosen_) c.clear();
  error_.clear();
  status_.clear();
}

const char* PacsBrowser::failedStep() const {
  switch (step_) {
    case Step::Search:
      return "Search";
    case Step::Series:
      return "The study's series";
    case Step::Open:
      break;
  }
  return "Open";
}

bool PacsBrowser::takeWindowRequest() { return std::exchange(windowRequested_, false); }

bool PacsBrowser::selectServer(const std::string& name) {
  for (std::size_t i = 0; i < servers_.size(); ++i)
    if (servers_[i].name == name) {
      selectServer(static_cast<int>(i));
      return true;
    }
  return false;
}

pacs::Options PacsBrowser::options() const {
  pacs::Options o = options_;
  o.progress = false;
  if (server_ >= 0) o.callingAet = servers_[static_cast<std::size_t>(server_)].callingAet;
  return o;
}

pacs::Server PacsBrowser::chosenServer() const {
  if (server_ < 0) throw InputError(serversFile_, "no server chosen");
  return pacs::parseServer(servers_[static_cast<std::size_t>(server_)].url);
}

void PacsBrowser::search() {
  if (running_ || server_ < 0) return;
  const pacs::Server server = chosenServer();
  const pacs::Options o = options();
  const pacs::StudyQuery q = query_;
  start(Step::Search, "searching " + servers_[static_cast<std::size_t>(server_)].name,
        [server, o, q](Outcome& out) { out.matches = pacs::findStudies(server, q, o); });
}

void PacsBrowser::chooseStudy(int index) {
  if (running_) return;
  series_.clear();
  for (std::string& c : chosen_) c.clear();
  study_ = index >= 0 && index < static_cast<int>(studies_.size()) ? index : -1;
  if (study_ < 0) return;
  const pacs::Server server = chosenServer();
  const pacs::Options o = options();
  const std::string uid =
      pacs::matchValue(studies_[static_cast<std::size_t>(study_)], "StudyInstanceUID");
  start(Step::Series, "asking for the study's series",
        [server, o, uid](Outcome& out) { out.matches = pacs::findSeries(server, uid, o); });
}

void PacsBrowser::setSeries(Role role, std::string seriesUid) {
  chosen_[static_cast<int>(role)] = std::move(seriesUid);
}

void PacsBrowser::chooseSeries(Role role, const std::string& selection) {
  if (study_ < 0) throw InputError(serversFile_, "no study chosen");
  const std::string uid =
      pacs::matchValue(studies_[static_cast<std::size_t>(study_)], "StudyInstanceUID");
  setSeries(role, pacs::matchValue(pacs::selectSeries(chosenServer(), series_, uid, selection),
                                   "SeriesInstanceUID"));
}

const std::string& PacsBrowser::chosen(Role role) const { return chosen_[static_cast<int>(role)]; }

std::string PacsBrowser::describeSeries(const std::string& seriesUid) const {
  if (seriesUid.empty()) return "none";
  for (const pacs::Match& s : series_)
    if (pacs::matchValue(s, "SeriesInstanceUID") == seriesUid) {
      const std::string number = pacs::matchValue(s, "SeriesNumber");
      std::string text =
          (number.empty() ? "" : "#" + number + "  ") + pacs::matchValue(s, "Modality");
      if (const std::string d = pacs::matchValue(s, "SeriesDescription"); !d.empty())
        text += "  " + d;
      if (const std::string n = pacs::matchValue(s, "NumberOfSeriesRelatedInstances"); !n.empty())
        text += "  (" + n + " images)";
      return text;
    }
  return seriesUid;
}

std::string PacsBrowser::describeStudy(const pacs::Match& s) {
  std::string text = personName(pacs::matchValue(s, "PatientName"));
  if (text.empty()) text = "(no name)";
  if (const std::string id = pacs::matchValue(s, "PatientID"); !id.empty()) text += "  ID " + id;
  if (const std::string d = pacs::matchValue(s, "StudyDate"); !d.empty())
    text += "  " + dicomDate(d);
  if (const std::string m = pacs::matchValue(s, "ModalitiesInStudy"); !m.empty()) text += "  " + m;
  if (const std::string d = pacs::matchValue(s, "StudyDescription"); !d.empty()) text += "  " + d;
  return text;
}

config::StudyConfig PacsBrowser::studyConfig() const {
  if (study_ < 0) throw InputError(serversFile_, "no study chosen");
  if (chosen(Role::Anatomical).empty())
    throw InputError(serversFile_, "no anatomical series chosen");
  const PacsServerEntry& server = servers_[static_cast<std::size_t>(server_)];
  const pacs::Match& s = studies_[static_cast<std::size_t>(study_)];
  config::StudyConfig study;
  // Who and what, as the reader knows the study: patient, description, else its modalities
  // and date; and from which server.
  const std::string patient = personName(pacs::matchValue(s, "PatientName"));
  study.name = patient.empty() ? pacs::matchValue(s, "PatientID") : patient;
  if (const std::string d = pacs::matchValue(s, "StudyDescription"); !d.empty())
    study.name += (study.name.empty() ? "" : " ") + d;
  if (study.name.empty()) {
    study.name = "PACS study";
    if (const std::string m = pacs::matchValue(s, "ModalitiesInStudy"); !m.empty())
      study.name += " " + m;
    if (const std::string d = pacs::matchValue(s, "StudyDate"); !d.empty())
      study.name += " " + dicomDate(d);
  }
  study.name += " (" + server.name + ")";
  auto source = [&](Role role) {
    config::VolumeSource v;
    v.pacs = server.url;
    v.study = pacs::matchValue(s, "StudyInstanceUID");
    v.series = chosen(role);
    return v;
  };
  study.anatomical = source(Role::Anatomical);
  if (!chosen(Role::Functional).empty()) {
    study.functional = source(Role::Functional);
    study.functionalKind = functionalKind;
    study.functional->frame = config::defaultFrame(functionalKind);
    study.registration.method = registration;
  }
  if (!chosen(Role::Segmentation).empty()) study.segmentation = source(Role::Segmentation);
  // As loadStudyConfig completes a config without views: the one default view, so the viewer
  // opens the study exactly as it opens the same config from a file.
  config::ViewConfig view;
  view.name = "view0";
  view.implied = true;
  study.render.views.push_back(view);
  return study;
}

void PacsBrowser::open() {
  if (running_) return;
  config::StudyConfig study;
  try {
    study = studyConfig();
  } catch (const InputError& e) {
    step_ = Step::Open;
    error_ = e.problem();
    return;
  }
  const pacs::Server server = chosenServer();
  const pacs::Options o = options();
  struct Wanted {
    Role role;
    std::string uid, total;  // total: the instances the server states ("" where it does not)
  };
  std::vector<Wanted> wanted;
  for (Role role : {Role::Anatomical, Role::Functional, Role::Segmentation})
    if (!chosen(role).empty()) {
      std::string total;
      for (const pacs::Match& m : series_)
        if (pacs::matchValue(m, "SeriesInstanceUID") == chosen(role))
          total = pacs::matchValue(m, "NumberOfSeriesRelatedInstances");
      wanted.push_back({role, chosen(role), total});
    }
  start(Step::Open, "opening", [this, server, o, wanted, study](Outcome& out) mutable {
    // Into the verified cache with this server's calling AE title first; the study loader
    // then reads each series from there, offline, as for `mvw view STUDY.json` (with the same
    // options, should a series have to be retrieved again).
    for (std::size_t i = 0; i < wanted.size(); ++i) {
      const std::string step = "retrieving the " + std::string(roleName(wanted[i].role)) +
                               " series (" + std::to_string(i + 1) + " of " +
                               std::to_string(wanted.size()) + ")";
      setActivity(step);
      {
        std::lock_guard lock(activityMutex_);
        fraction_ = wanted[i].total.empty() ? -1.0f : 0.0f;
      }
      pacs::Options withProgress = o;
      const std::string total = wanted[i].total;
      withProgress.onProgress = [this, step, total](const pacs::Transfer& t) {
        char text[128];
        const double mb = static_cast<double>(t.bytes) / 1e6;
        std::snprintf(text, sizeof text, ": %d%s%s images, %.1f MB, %.1f MB/s", t.instances,
                      total.empty() ? "" : " of ", total.c_str(), mb,
                      t.seconds > 0 ? mb / t.seconds : 0.0);
        setActivity(step + text);
        std::lock_guard lock(activityMutex_);
        lastProgress_ = step + text;
        const double stated = total.empty() ? 0.0 : std::atof(total.c_str());
        fraction_ = stated > 0 ? static_cast<float>(std::min(1.0, t.instances / stated)) : -1.0f;
      };
      pacs::cachedSeries(server, study.anatomical.study, wanted[i].uid, withProgress);
    }
    setActivity(study.registration.method == config::RegistrationMethod::None
                    ? "reading the series"
                    : "reading the series and registering them");
    auto session = std::make_unique<study::Session>(std::move(study));
    session->load(o);
    out.session = std::move(session);
  });
}

void PacsBrowser::setActivity(std::string what) {
  std::lock_guard lock(activityMutex_);
  activity_ = std::move(what);
}

float PacsBrowser::progress() const {
  std::lock_guard lock(activityMutex_);
  return running_ ? fraction_ : -1.0f;
}

bool PacsBrowser::retrieving() const {
  std::lock_guard lock(activityMutex_);
  return running_ && !lastProgress_.empty();
}

std::string PacsBrowser::activity() const {
  if (!running_) return {};
  std::string what;
  {
    std::lock_guard lock(activityMutex_);
    what = activity_;
  }
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, ", %.1f s",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
  return what + seconds + "...";
}

void PacsBrowser::start(Step step, std::string what, std::function<void(Outcome&)> job) {
  running_ = true;
  done_ = false;
  step_ = step;
  outcome_ = {};
  error_.clear();
  status_.clear();
  setActivity(std::move(what));
  {
    std::lock_guard lock(activityMutex_);
    lastProgress_.clear();
    fraction_ = -1.0f;
  }
  started_ = std::chrono::steady_clock::now();
  thread_ = std::jthread([this, job = std::move(job)] {
    try {
      job(outcome_);
    } catch (const std::exception& e) {
      outcome_.error = e.what();
    } catch (...) {
      outcome_.error = "unknown error";
    }
    done_ = true;
  });
}

std::unique_ptr<study::Session> PacsBrowser::poll() {
  if (!running_ || !done_) return nullptr;
  thread_.join();
  running_ = false;
  Outcome out = std::exchange(outcome_, {});
  if (!out.error.empty()) {
    error_ = out.error;
    return nullptr;
  }
  switch (step_) {
    case Step::Search:
      takeStudies(std::move(out.matches));
      break;
    case Step::Series:
      takeSeries(std::move(out.matches));
      break;
    case Step::Open:
      status_ = "opened " + out.session->config().name;
      return std::move(out.session);
  }
  return nullptr;
}

void PacsBrowser::takeStudies(std::vector<pacs::Match> studies) {
  studies_ = std::move(studies);
  study_ = -1;
  series_.clear();
  for (std::string& c : chosen_) c.clear();
  status_ = countOf(static_cast<long long>(studies_.size()), "study", "studies");
}

void PacsBrowser::takeSeries(std::vector<pacs::Match> series) {
  series_ = std::move(series);
  for (std::string& c : chosen_) c.clear();
  status_ = std::to_string(series_.size()) + " series";
  for (const char* modality : {"CT", "MR"})
    for (const pacs::Match& s : series_)
      if (chosen(Role::Anatomical).empty() && pacs::matchValue(s, "Modality") == modality)
        setSeries(Role::Anatomical, pacs::matchValue(s, "SeriesInstanceUID"));
  for (const char* modality : {"PT", "NM"})
    for (const pacs::Match& s : series_)
      if (chosen(Role::Functional).empty() && pacs::matchValue(s, "Modality") == modality) {
        setSeries(Role::Functional, pacs::matchValue(s, "SeriesInstanceUID"));
        functionalKind = std::string(modality) == "PT" ? config::FunctionalKind::Pet
                                                       : config::FunctionalKind::Spect;
      }
  // A PET (or SPECT) without a CT or MR is read alone, as its own anatomy.
  if (chosen(Role::Anatomical).empty()) std::swap(chosen_[0], chosen_[1]);
}

void PacsBrowser::writeReport(const std::filesystem::path& file) const {
  json j;
  j["servers_file"] = serversFile_.string();
  j["servers_problem"] = serversProblem_;
  j["server"] = server_ >= 0 ? servers_[static_cast<std::size_t>(server_)].name : "";
  j["studies"] = studies_;
  j["study"] =
      study_ >= 0 ? pacs::matchValue(studies_[static_cast<std::size_t>(study_)], "StudyInstanceUID")
                  : std::string();
  j["series"] = series_;
  for (Role role : {Role::Anatomical, Role::Functional, Role::Segmentation})
    j["chosen"][roleName(role)] = chosen(role);
  j["registration"] = config::toString(registration);
  j["status"] = status_;
  {
    std::lock_guard lock(activityMutex_);
    j["last_progress"] = lastProgress_;
  }
  j["error"] = error_;
  j["busy"] = running_;
  j["activity"] = activity();
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << j.dump(2) << "\n";
  if (!out) throw InputError(file, "cannot write the PACS report");
}

std::unique_ptr<study::Session> PacsBrowser::wait() {
  while (running_ && !done_) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return poll();
}

}  // namespace mvw::viewer
