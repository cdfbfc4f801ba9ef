#include "PacsCommand.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvw/config/ServerList.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/pacs/MatchTable.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::app {

namespace {

struct PacsCli {
  std::string server;
  pacs::Options options;
  pacs::StudyQuery query;
  std::vector<std::string> series;
  std::filesystem::path out;
  std::vector<std::filesystem::path> files;
  bool json = false;
  bool quiet = false;
};

void addConnection(CLI::App* cmd, PacsCli& o) {
  cmd->add_option("SERVER", o.server,
                  "http(s)://host:port/PATH (DICOMweb), dicom://AET@host:port (DIMSE), or the name "
                  "of a server saved in servers.json (as the viewer saves it)")
      ->required();
  addServerOptions(*cmd, o.options);
  cmd->add_option("--connect-timeout", o.options.connectTimeoutS,
                  "seconds to wait for the connection (default 10)")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->add_option("--read-timeout", o.options.readTimeoutS,
                  "seconds to wait for the next bytes of an answer (default 60)")
      ->check(CLI::Range(0.1, 86400.0));
  cmd->add_flag("-q,--quiet", o.quiet, "no progress on stderr");
}

// "mvw pacs store: skipped 8 files that are not DICOM: 6 .png, 1 .json (render.json), ...": by
// kind, most first, a kind of one file named, so an orbit's frames do not hide render.json.
std::string skippedSummary(const std::vector<std::filesystem::path>& skipped) {
  std::map<std::string, std::vector<std::filesystem::path>> byKind;
  for (const std::filesystem::path& f : skipped)
    byKind[f.extension().empty() ? "(no extension)" : f.extension().string()].push_back(f);
  std::vector<std::pair<std::string, std::vector<std::filesystem::path>>> kinds(byKind.begin(),
                                                                                byKind.end());
  std::stable_sort(kinds.begin(), kinds.end(),
                   [](const auto& a, const auto& b) { return a.second.size() > b.second.size(); });
  std::string text = "mvw pacs store: skipped " +
                     countOf(static_cast<long long>(skipped.size()), "file") +
                     (skipped.size() == 1 ? " that is" : " that are") + " not DICOM:";
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const auto& [kind, files] = kinds[i];
    text += (i ? ", " : " ") + std::to_string(files.size()) + " " + kind;
    if (files.size() == 1) text += " (" + files[0].filename().string() + ")";
  }
  return text;
}

}  // namespace

void addServerOptions(CLI::App& cmd, pacs::Options& options) {
  cmd.add_option("--calling-aet", options.callingAet, "DIMSE: mvw's AE title (default MVW)")
      ->check([](const std::string& s) {
        return pacs::isAeTitle(s) ? std::string()
                                  : std::string("an AE title has 1 to 16 characters");
      });
  cmd.add_flag("--insecure", options.insecure,
               "HTTPS: do not verify the server's certificate (said on stderr)");
}

void addPacsCommand(CLI::App& app) {
  auto o = std::make_shared<PacsCli>();
  CLI::App* cmd = app.add_subcommand(
      "pacs",
      "Query and retrieve studies from a PACS (DICOMweb or DIMSE); credentials from "
      "MVW_PACS_USER/MVW_PACS_PASSWORD or MVW_PACS_CREDENTIALS; exit 3 when the server "
      "fails");
  cmd->require_subcommand(1);

  CLI::App* echo = cmd->add_subcommand("echo", "C-ECHO, or a QIDO-RS request: the round trip");
  addConnection(echo, *o);
  echo->callback([o] {
    const pacs::Server server = config::resolveServer(o->server);
    const double s = pacs::echo(server, o->options);
    std::printf("%s answered in %.1f ms\n", server.text.c_str(), s * 1000.0);
  });

  CLI::App* find =
      cmd->add_subcommand("find", "Studies matching the keys, or with --study that study's series");
  addConnection(find, *o);
  find->add_option("--patient-id", o->query.patientId, "Patient ID");
  find->add_option("--patient-name", o->query.patientName, "Patient's name (wildcards * ?)");
  find->add_option("--study-date", o->query.studyDate, "YYYYMMDD or YYYYMMDD-YYYYMMDD");
  find->add_option("--modality", o->query.modality, "a modality in the study (CT, PT, MR...)");
  find->add_option("--accession", o->query.accession, "Accession Number");
  find->add_option("--study", o->query.studyUid, "a Study Instance UID: its series");
  find->add_flag("--json", o->json, "one JSON object per match, keyed by DICOM keyword");
  find->callback([o] {
    const pacs::Server server = config::resolveServer(o->server);
    if (!o->query.studyUid.empty()) {
      pacs::printMatches(std::cout, pacs::findStudySeries(server, o->query.studyUid, o->options),
                         o->json, true);
    } else {
      pacs::printMatches(std::cout, pacs::findStudies(server, o->query, o->options), o->json,
                         false);
    }
  });

  CLI::App* get = cmd->add_subcommand(
      "get",
      "Every instance of the chosen series (all without --series) into DIR, one file per "
      "instance named by its SOP Instance UID");
  addConnection(get, *o);
  get->add_option("--study", o->query.studyUid, "the Study Instance UID")->required();
  get->add_option("--series", o->series,
                  "a series: its UID, number, modality or part of its description (repeatable)");
  get->add_option("-o,--output", o->out, "the folder to write into")->required();
  get->add_option("--move-to", o->options.moveToAet,
                  "DIMSE: retrieve by C-MOVE to this AE title (mvw's storage SCP; needs --port)");
  get->add_option("--port", o->options.movePort, "the storage SCP's port for --move-to")
      ->check(CLI::Range(1, 65535));
  get->callback([o] {
    const pacs::Server server = config::resolveServer(o->server);
    if (!o->options.moveToAet.empty() &&
        (o->options.movePort == 0 || server.protocol != pacs::Protocol::Dimse))
      throw InputError("--move-to", "needs --port P and a dicom:// server");
    o->options.progress = !o->quiet;
    std::cout << pacs::transferSummary("retrieved", pacs::get(server, o->query.studyUid, o->series,
                                                              o->out, o->options))
              << "\n";
  });

  CLI::App* store = cmd->add_subcommand(
      "store",
      "DICOM files (or the DICOM files under folders, the rest skipped) to the server: "
      "STOW-RS or C-STORE");
  addConnection(store, *o);
  store->add_option("FILE", o->files, "DICOM files or folders")->required();
  store->callback([o] {
    const pacs::Server server = config::resolveServer(o->server);
    // A folder a command wrote holds more than DICOM (mvw render --dicom: PNGs, render.json):
    // its DICOM files go, the rest is named as skipped.
    const pacs::StoreFiles chosen = pacs::storeFiles(o->files);
    if (!chosen.skipped.empty()) std::cerr << skippedSummary(chosen.skipped) << "\n";
    std::cout << pacs::transferSummary("stored", pacs::store(server, chosen, o->options)) << "\n";
  });

  // The cache folder is main's --cache (given before or after the command's name).
  CLI::App* cache = cmd->add_subcommand(
      "cache",
      "The cache of PACS series: its folder and its quarantine (series whose files failed to "
      "read after they were cached; each is retrieved again on its next read)");
  auto clear = std::make_shared<bool>(false);
  cache->add_flag("--clear-quarantine", *clear, "empty the quarantine");
  cache->callback([&app, clear] {
    pacs::Options options;
    if (const CLI::Option* given = app.get_option_no_throw("--cache"); given && given->count())
      options.cacheDir = given->as<std::string>();
    const std::filesystem::path quarantine = pacs::quarantineRoot(options);
    const pacs::QuarantineSize size =
        *clear ? pacs::clearQuarantine(options) : pacs::quarantineSize(options);
    const std::string held = countOf(size.series, "series", "series") + ", " +
                             fixedNumber(static_cast<double>(size.bytes) / 1e6, 1) + " MB";
    std::cout << "cache: " << pacs::cacheRoot(options).string() << "\n"
              << (*clear ? "quarantine emptied: " : "quarantine: ") << quarantine.string() << " ("
              << held << ")\n";
  });
}

}  // namespace mvw::app
