#pragma once
// The viewer's PACS browser (issue 37 item 3), without a window or GL: the server list
// (servers.json), the study search, a study's series, the series chosen as the anatomical, the
// functional volume and the segmentation with the registration rule, and the study config they
// make: a config naming PACS series (pacs, study, series), loaded exactly as `mvw view
// STUDY.json` loads one (study::Session, through the verified cache). Every network step (the
// search, a study's series, the retrieve and the load) runs on a background thread, one at a
// time, so the window keeps drawing; poll() hands its outcome over once it has ended. The panel
// (PacsPanel) and the script (ViewerScript's pacs-* commands) both act through this class.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "mvw/config/ServerList.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/study/Session.h"

namespace mvw::viewer {

// One server of servers.json, read and written by modules/config (ServerList.h).
using PacsServerEntry = config::SavedServer;
using config::defaultServersFile;
inline std::vector<PacsServerEntry> loadServers(const std::filesystem::path& file) {
  return config::readServerList(file);
}

class PacsBrowser {
 public:
  enum class Role { Anatomical, Functional, Segmentation };
  static const char* roleName(Role role);  // anatomical, functional, segmentation

  // `options`: the command line's --cache, --connect-timeout and --read-timeout, which every
  // step (and the study an open loads) uses.
  explicit PacsBrowser(pacs::Options options = {});
  ~PacsBrowser();  // a running step is waited for (its thread joined)
  PacsBrowser(const PacsBrowser&) = delete;
  PacsBrowser& operator=(const PacsBrowser&) = delete;

  // The server list and the file it came from; `problem`: why the default file could not be
  // used (the panel shows it; the list is then empty).
  void setServers(std::vector<PacsServerEntry> servers, std::filesystem::path file,
                  std::string problem = {});
  const std::vector<PacsServerEntry>& servers() const { return servers_; }
  const std::filesystem::path& serversFile() const { return serversFile_; }
  const std::string& serversProblem() const { return serversProblem_; }
  // Choosing a server forgets the studies and series found on another.
  void selectServer(int index);
  bool selectServer(const std::string& name);  // false: no server of that name
  int server() const { return server_; }       // -1: none chosen

  // The PACS window asked to show (a script's pacs-* line); the window loop takes it.
  void requestWindow() { windowRequested_ = true; }
  bool takeWindowRequest();

  // The options every step uses: those the browser was made with (`--cache`, the time-outs),
  // with the server's calling AE title and no progress on stderr.
  pacs::Options options() const;

  // The search (findStudies) with the query as set; the studies replace the last ones.
  pacs::StudyQuery& query() { return query_; }
  void search();
  const std::vector<pacs::Match>& studies() const { return studies_; }
  // A study of the list (its series are asked for: findSeries); -1: none.
  void chooseStudy(int index);
  int study() const { return study_; }
  const std::vector<pacs::Match>& series() const { return series_; }
  // What a search or a study's series query found (poll() gives them their outcome; tests give
  // them by hand). takeSeries makes a first choice a reader would: the first CT (else MR) as
  // the anatomy, the first PT (else NM) as the functional volume; without a CT or MR, that PT
  // as the anatomy alone. No segmentation: the reader chooses one.
  void takeStudies(std::vector<pacs::Match> studies);
  void takeSeries(std::vector<pacs::Match> series);

  // The series a role takes: its SeriesInstanceUID, "" for none. chooseSeries by a selection
  // as `mvw pacs get --series` takes it (UID, number, modality, part of the description):
  // InputError when it matches none or several of the study's series.
  void setSeries(Role role, std::string seriesUid);
  void chooseSeries(Role role, const std::string& selection);
  const std::string& chosen(Role role) const;
  // The chosen series's line for the panel: "3  CT  Cranium CT  (108 images)"; "none".
  std::string describeSeries(const std::string& seriesUid) const;
  static std::string describeStudy(const pacs::Match& study);
  static std::string dicomDate(const std::string& yyyymmdd);  // "2026-11-30"
  // The PACS window's tables as text (the window only draws them). A study's row: patient
  // (the name's ^ as spaces; "(no name)"), patient ID, date (dicomDate), modalities,
  // description, number of series. A series's row: number, modality, description, images.
  static std::vector<std::string> studyRow(const pacs::Match& study);
  static std::vector<std::string> seriesRow(const pacs::Match& series);
  // Whether a series (its UID) takes a role.
  bool isChosen(const std::string& seriesUid) const;
  // The search's study date, the query's DICOM range "FROM-TO", as its two ends (either may
  // be empty: from onwards, up to; a single date is its FROM), and set from them (both empty:
  // any date).
  std::pair<std::string, std::string> studyDateRange() const;
  void setStudyDateRange(const std::string& from, const std::string& to);

  config::RegistrationMethod registration = config::RegistrationMethod::None;
  config::FunctionalKind functionalKind = config::FunctionalKind::Pet;

  // The study config of the choices: each chosen series named by the server's SERVER, the
  // study's UID and the series's UID; the study's name from the patient and the study. Throws
  // InputError (naming the servers file) when no anatomical series is chosen.
  config::StudyConfig studyConfig() const;
  // Retrieves the chosen series into the verified cache, then loads them as a study
  // (study::Session::load): the outcome comes from poll().
  void open();

  // Whether a step runs or has ended with an outcome poll() has not yet taken.
  bool busy() const { return running_; }
  // The running retrieve's fraction of its series (instances of those the server states), or
  // -1 when none runs or the server states no count.
  float progress() const;
  // Whether the running open's retrieve has received an instance (its progress shows).
  bool retrieving() const;
  // What the running step does, with its time ("retrieving the functional series (2 of 2),
  // 3.1 s"); "" when idle.
  std::string activity() const;
  // The last step's failure (the server's message), or "", and what failed ("Search",
  // "The study's series", "Open").
  const std::string& error() const { return error_; }
  const char* failedStep() const;
  // A failure after the step (the viewer could not show the loaded study): said as error().
  void fail(std::string why) { error_ = std::move(why), status_.clear(); }
  // What the last step did ("3 studies", "opened ..."), or "".
  const std::string& status() const { return status_; }
  // Called once a frame: takes the ended step's outcome; a loaded study when an open ended
  // well (the viewer shows it in place of its current one).
  std::unique_ptr<study::Session> poll();
  // The browser's state as JSON (tests): server, studies, study, series, chosen, registration,
  // status, error, and the last retrieve progress shown (last_progress).
  void writeReport(const std::filesystem::path& file) const;
  // Waits for the running step (tests without a window), then poll().
  std::unique_ptr<study::Session> wait();

 private:
  struct Outcome {
    std::vector<pacs::Match> matches;
    std::unique_ptr<study::Session> session;
    std::string error;
  };
  enum class Step { Search, Series, Open };
  void start(Step step, std::string what, std::function<void(Outcome&)> job);
  pacs::Server chosenServer() const;
  void setActivity(std::string what);

  pacs::Options options_;
  std::vector<PacsServerEntry> servers_;
  std::filesystem::path serversFile_;
  std::string serversProblem_;
  int server_ = -1;
  pacs::StudyQuery query_;
  std::vector<pacs::Match> studies_;
  int study_ = -1;
  std::vector<pacs::Match> series_;
  std::string chosen_[3];
  std::string error_, status_;
  bool windowRequested_ = false;

  bool running_ = false;
  Step step_ = Step::Search;
  std::chrono::steady_clock::time_point started_;
  mutable std::mutex activityMutex_;
  std::string activity_;      // written by the worker (the retrieve's steps), read by the panel
  std::string lastProgress_;  // the last retrieve progress said (the report)
  float fraction_ = -1.0f;    // of the series being retrieved
  std::atomic<bool> done_{false};
  Outcome outcome_;  // written by the worker before done_, read after it
  std::jthread thread_;
};

}  // namespace mvw::viewer
