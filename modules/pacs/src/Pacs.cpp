#include "mvw/pacs/Pacs.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "Internal.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/Interrupt.h"
#include "mvw/io/StagedFolder.h"

namespace fs = std::filesystem;

namespace mvw::pacs {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A folder name for one server: its text's safe characters and a hash, so two servers never
// share a folder and no server text becomes a path.
std::string serverKey(const Server& server) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : server.text) h = (h ^ c) * 1099511628211ull;
  std::string safe;
  for (char c : server.text)
    if (std::isalnum(static_cast<unsigned char>(c)) && safe.size() < 40) safe += c;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return safe + "-" + hex;
}

std::string hexOf(const std::string& text) {
  std::string out;
  char b[3];
  for (unsigned char c : text.substr(0, 100)) {
    std::snprintf(b, sizeof b, "%02x", c);
    out += b;
  }
  return out;
}

}  // namespace

Server parseServer(const std::string& text) {
  Server s;
  s.text = text;
  static const std::regex web(R"(^(https?)://([^/@\s]+)(/[^\s@]*)?$)", std::regex::icase);
  static const std::regex dimse(
      R"(^dicom://([^@\s]{1,16})@([A-Za-z0-9.\-]+|\[[0-9a-fA-F:]+\]):([0-9]{1,5})$)",
      std::regex::icase);
  std::smatch m;
  if (text.find('@') != std::string::npos && lower(text).rfind("http", 0) == 0)
    throw InputError(text.substr(0, text.find("//") + 2) + "...",
                     "credentials in the server URL are not accepted: set MVW_PACS_USER and "
                     "MVW_PACS_PASSWORD, or MVW_PACS_CREDENTIALS (a file only its owner can read)");
  if (std::regex_match(text, m, web)) {
    s.protocol = Protocol::DicomWeb;
    s.baseUrl = text;
    while (!s.baseUrl.empty() && s.baseUrl.back() == '/') s.baseUrl.pop_back();
    return s;
  }
  if (std::regex_match(text, m, dimse)) {
    s.protocol = Protocol::Dimse;
    s.calledAet = m[1];
    s.host = m[2];
    if (s.host.front() == '[') s.host = s.host.substr(1, s.host.size() - 2);
    s.port = std::stoi(m[3]);
    if (s.port < 1 || s.port > 65535) throw InputError(text, "the port must be 1 .. 65535");
    return s;
  }
  throw InputError(text,
                   "is not a server: give http(s)://host:port/PATH (DICOMweb) or "
                   "dicom://AET@host:port (DIMSE)");
}

bool isUid(const std::string& text) {
  if (text.empty() || text.size() > 64 || text.front() == '.' || text.back() == '.') return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.') {
      if (text[i + 1] == '.') return false;
    } else if (c < '0' || c > '9') {
      return false;
    }
  }
  return true;
}

bool isAeTitle(const std::string& text) { return !text.empty() && text.size() <= 16; }

std::string matchValue(const Match& match, const char* keyword) {
  const auto it = match.find(keyword);
  return it == match.end() ? std::string() : it->second;
}

fs::path cacheRoot(const Options& options) {
  if (!options.cacheDir.empty()) return options.cacheDir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
    return fs::path(xdg) / "mvw" / "dicom";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "mvw" / "dicom";
  throw InputError("$HOME", "is not set: give the cache folder with --cache DIR");
}

double echo(const Server& server, const Options& options) {
  return server.protocol == Protocol::DicomWeb ? detail::webEcho(server, options)
                                               : detail::dimseEcho(server, options);
}

namespace {

std::vector<Match> find(const Server& server, const std::string& level, const Match& keys,
                        const Options& options) {
  return server.protocol == Protocol::DicomWeb ? detail::webFind(server, level, keys, options)
                                               : detail::dimseFind(server, level, keys, options);
}

void requireUid(const std::string& uid, const std::string& what) {
  if (!isUid(uid)) throw InputError(what, "'" + uid + "' is not a DICOM UID");
}

}  // namespace

std::vector<Match> findStudies(const Server& server, const StudyQuery& q, const Options& options) {
  if (!q.studyUid.empty()) requireUid(q.studyUid, "--study");
  Match keys{{"StudyInstanceUID", q.studyUid},   {"PatientID", q.patientId},
             {"PatientName", q.patientName},     {"StudyDate", q.studyDate},
             {"ModalitiesInStudy", q.modality},  {"AccessionNumber", q.accession},
             {"StudyDescription", ""},           {"StudyTime", ""},
             {"NumberOfStudyRelatedSeries", ""}, {"NumberOfStudyRelatedInstances", ""}};
  return find(server, "STUDY", keys, options);
}

std::vector<Match> findSeries(const Server& server, const std::string& studyUid,
                              const Options& options) {
  requireUid(studyUid, "--study");
  Match keys{{"StudyInstanceUID", studyUid}, {"SeriesInstanceUID", ""},
             {"SeriesNumber", ""},           {"Modality", ""},
             {"SeriesDescription", ""},      {"NumberOfSeriesRelatedInstances", ""}};
  std::vector<Match> series = find(server, "SERIES", keys, options);
  for (const Match& m : series) {
    auto it = m.find("SeriesInstanceUID");
    if (it == m.end() || !isUid(it->second))
      throw ServiceError(server.text + ": answered a series without a valid SeriesInstanceUID");
  }
  std::sort(series.begin(), series.end(), [](const Match& a, const Match& b) {
    auto num = [](const Match& m) {
      auto it = m.find("SeriesNumber");
      return it == m.end() ? 0L : std::strtol(it->second.c_str(), nullptr, 10);
    };
    return num(a) < num(b);
  });
  return series;
}

std::vector<Match> findStudySeries(const Server& server, const std::string& studyUid,
                                   const Options& options) {
  std::vector<Match> series = findSeries(server, studyUid, options);
  if (series.empty()) {
    // An unknown study and a study without series read alike: say which.
    StudyQuery q;
    q.studyUid = studyUid;
    if (findStudies(server, q, options).empty())
      throw InputError(server.text, "has no study " + studyUid);
  }
  return series;
}

std::vector<Match> findInstances(const Server& server, const std::string& studyUid,
                                 const std::string& seriesUid, const Options& options) {
  requireUid(studyUid, "--study");
  requireUid(seriesUid, "--series");
  Match keys{{"StudyInstanceUID", studyUid},
             {"SeriesInstanceUID", seriesUid},
             {"SOPInstanceUID", ""},
             {"InstanceNumber", ""}};
  std::vector<Match> instances = find(server, "IMAGE", keys, options);
  std::set<std::string> seen;
  for (const Match& m : instances) {
    auto it = m.find("SOPInstanceUID");
    // A UID like "../x" or one of 70 characters is refused here, before it can name a file.
    if (it == m.end() || !isUid(it->second))
      throw ServiceError(server.text + ": answered an instance whose SOPInstanceUID is not a UID" +
                         (it == m.end() ? std::string() : " ('" + it->second.substr(0, 80) + "')"));
    if (!seen.insert(it->second).second)
      throw ServiceError(server.text + ": listed the instance " + it->second + " twice");
  }
  return instances;
}

Match selectSeries(const Server& server, const std::vector<Match>& series,
                   const std::string& studyUid, const std::string& selection) {
  std::vector<const Match*> hits;
  for (const Match& m : series)
    if (matchValue(m, "SeriesInstanceUID") == selection) return m;
  for (const Match& m : series)
    if (matchValue(m, "SeriesNumber") == selection) hits.push_back(&m);
  if (hits.empty())
    for (const Match& m : series)
      if (lower(matchValue(m, "Modality")) == lower(selection)) hits.push_back(&m);
  if (hits.empty())
    for (const Match& m : series)
      if (!selection.empty() &&
          lower(matchValue(m, "SeriesDescription")).find(lower(selection)) != std::string::npos)
        hits.push_back(&m);
  if (hits.size() == 1) return *hits.front();
  std::string list;
  for (const Match& m : series)
    list += "\n  " + matchValue(m, "SeriesNumber") + " " + matchValue(m, "Modality") + " '" +
            matchValue(m, "SeriesDescription") + "' " + matchValue(m, "SeriesInstanceUID");
  throw InputError(server.text, std::string(hits.empty() ? "no series" : "several series") +
                                    " of study " + studyUid + " match '" + selection +
                                    "'; its series:" + list);
}

namespace {

// The series of `studyUid` the selections name (every series for none).
std::vector<Match> resolveSeries(const Server& server, const std::string& studyUid,
                                 const std::vector<std::string>& selections,
                                 const Options& options) {
  std::vector<Match> all = findSeries(server, studyUid, options);
  if (all.empty()) throw InputError(server.text, "has no study " + studyUid);
  if (selections.empty()) return all;
  std::vector<Match> chosen;
  for (const std::string& s : selections) {
    Match m = selectSeries(server, all, studyUid, s);
    const bool seen = std::any_of(chosen.begin(), chosen.end(), [&](const Match& c) {
      return c.at("SeriesInstanceUID") == m.at("SeriesInstanceUID");
    });
    if (!seen) chosen.push_back(std::move(m));
  }
  return chosen;
}

// The instance count a series match states (NumberOfSeriesRelatedInstances), or -1 where the
// server gives none: then its instances are listed. A count saves the listing, which costs a
// server more than the retrieve itself (Orthanc: 0.7 s for 299 instances, the retrieve 0.1 s).
long statedCount(const Match& series) {
  auto it = series.find("NumberOfSeriesRelatedInstances");
  if (it == series.end() || it->second.empty() ||
      it->second.find_first_not_of("0123456789") != std::string::npos || it->second.size() > 9)
    return -1;
  return std::stol(it->second);
}

void retrieve(const Server& server, const std::string& studyUid, const std::string& seriesUid,
              const std::vector<std::string>& instances, detail::Receiver& receiver,
              const Options& options) {
  if (server.protocol == Protocol::DicomWeb)
    detail::webRetrieve(server, studyUid, seriesUid, instances, receiver, options);
  else
    detail::dimseRetrieve(server, studyUid, seriesUid, instances, receiver, options);
}

std::set<std::string> instanceUids(const std::vector<Match>& instances) {
  std::set<std::string> uids;
  for (const Match& m : instances) uids.insert(m.at("SOPInstanceUID"));
  return uids;
}

// Why the file of instance `uid` does not count as received (detail::checkInstance, then the
// UIDs asked for), "" when it does.
std::string instanceProblem(const fs::path& file, const std::string& uid,
                            const std::string& studyUid, const std::string& seriesUid) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return "it is missing";
  const detail::InstanceCheck check = detail::checkInstance(file);
  if (!check.ok()) return check.problem;
  const detail::FileUids& got = *check.uids;
  if (got.sopInstance != uid) return "it carries the SOP Instance UID " + got.sopInstance;
  if (got.series != seriesUid) return "it is of series " + got.series;
  if (got.study != studyUid) return "it is of study " + got.study;
  return {};
}

// Every listed instance present in `dir` as <uid>.dcm and counting as received; the files that
// fail are removed (they are fetched again).
std::vector<std::string> missingInstances(const fs::path& dir, const std::set<std::string>& uids,
                                          const std::string& studyUid,
                                          const std::string& seriesUid) {
  std::vector<std::string> missing;
  for (const std::string& uid : uids) {
    const fs::path file = dir / (uid + ".dcm");
    if (!instanceProblem(file, uid, studyUid, seriesUid).empty()) {
      std::error_code ec;
      fs::remove(file, ec);
      missing.push_back(uid);
    }
  }
  return missing;
}

// Why a complete series folder does not verify any more: its first instance that fails, named.
std::string unverified(const fs::path& dir, const std::set<std::string>& uids,
                       const std::string& studyUid, const std::string& seriesUid) {
  for (const std::string& uid : uids) {
    const fs::path file = dir / (uid + ".dcm");
    if (std::string why = instanceProblem(file, uid, studyUid, seriesUid); !why.empty())
      return file.filename().string() + ": " + why;
  }
  return {};
}

std::uint64_t treeBytes(const fs::path& dir) {
  std::uint64_t bytes = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    std::error_code sizeEc;
    if (it->is_regular_file(sizeEc)) {
      const auto n = it->file_size(sizeEc);
      if (!sizeEc) bytes += n;
    }
  }
  return bytes;
}

// UTC to the microsecond, fixed width: quarantine entries sort oldest first by name.
std::string utcStamp() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto us =
      std::chrono::duration_cast<std::chrono::microseconds>(now.time_since_epoch()).count() %
      1000000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y%m%dT%H%M%S", &tm);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%06dZ", text, static_cast<int>(us));
  return out;
}

// The entries of the quarantine, oldest first.
std::vector<fs::path> quarantined(const fs::path& root) {
  std::vector<fs::path> entries;
  std::error_code ec;
  for (auto it = fs::directory_iterator(root, ec); !ec && it != fs::end(it); it.increment(ec))
    if (it->is_directory(ec)) entries.push_back(it->path());
  std::sort(entries.begin(), entries.end());
  return entries;
}

// The listed instances with no <uid>.dcm in `dir` (each file there was checked on receipt).
std::vector<std::string> absentInstances(const fs::path& dir, const std::set<std::string>& uids) {
  std::vector<std::string> absent;
  std::error_code ec;
  for (const std::string& uid : uids)
    if (!fs::is_regular_file(dir / (uid + ".dcm"), ec)) absent.push_back(uid);
  return absent;
}

}  // namespace

Transfer get(const Server& server, const std::string& studyUid,
             const std::vector<std::string>& series, const fs::path& outDir,
             const Options& options) {
  requireUid(studyUid, "--study");
  const std::vector<Match> chosen = resolveSeries(server, studyUid, series, options);
  std::set<std::string> seriesUids;
  for (const Match& m : chosen) seriesUids.insert(m.at("SeriesInstanceUID"));
  // Received into a folder inside the output folder and moved out once every series is
  // complete: a failed retrieve leaves no instance of it.
  io::StagedFolder staging(outDir, {.place = io::StagedFolder::Place::Inside});
  detail::Receiver receiver(server, staging.path(), {studyUid, seriesUids}, options.progress);
  receiver.setOnProgress(options.onProgress);
  for (const Match& m : chosen) {
    const std::string& uid = m.at("SeriesInstanceUID");
    // Complete: as many instances as the server states, each of this series (the receiver
    // refused any other), or every instance it lists.
    const long stated = statedCount(m);
    std::set<std::string> listed;
    if (stated < 0) listed = instanceUids(findInstances(server, studyUid, uid, options));
    retrieve(server, studyUid, uid, {}, receiver, options);
    const long expected = stated >= 0 ? stated : static_cast<long>(listed.size());
    for (const std::string& sop : listed)
      if (!fs::exists(staging.path() / (sop + ".dcm")))
        throw ServiceError(server.text + ": the retrieve of series " + uid +
                           " ended without its instance " + sop);
    if (receiver.countOf(uid) != expected)
      throw ServiceError(server.text + ": the retrieve of series " + uid + " ended with " +
                         std::to_string(receiver.countOf(uid)) + " of the " +
                         countOf(expected, "instance") + " it holds");
  }
  // The caller says what was retrieved (transferSummary): a closing count here would be a
  // second final line saying the same.
  receiver.clearLine();
  staging.commit();
  return receiver.transfer();
}

Transfer store(const Server& server, const std::vector<fs::path>& inputs, const Options& options) {
  return store(server, storeFiles(inputs), options);
}

Transfer store(const Server& server, const StoreFiles& chosen, const Options& options) {
  const std::vector<fs::path>& files = chosen.files;
  const auto start = std::chrono::steady_clock::now();
  if (server.protocol == Protocol::DicomWeb)
    detail::webStore(server, files, options);
  else
    detail::dimseStore(server, files, options);
  Transfer t;
  t.instances = static_cast<int>(files.size());
  t.bytes = chosen.bytes;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

fs::path cachedSeries(const Server& server, const std::string& studyUid,
                      const std::string& selection, const Options& options) {
  requireUid(studyUid, server.text + " study");
  const fs::path studyDir = detail::studyFolder(server, studyUid, options);
  const fs::path selectionFile = studyDir / ("selection-" + hexOf(selection));
  // A series folder complete and verified; one that was complete and no longer verifies is
  // moved into the quarantine (said), so it is retrieved again instead of failing every read.
  auto completeFolder = [&](const std::string& seriesUid) -> std::optional<fs::path> {
    const fs::path dir = studyDir / seriesUid;
    std::set<std::string> uids;
    {
      std::ifstream in(dir / ".complete");
      if (!in) return std::nullopt;
      for (std::string line; std::getline(in, line);)
        if (isUid(line)) uids.insert(line);
    }
    std::string why = uids.empty() ? std::string("its .complete lists no instance")
                                   : unverified(dir, uids, studyUid, seriesUid);
    if (why.empty()) {
      std::size_t files = 0;
      for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".dcm") ++files;
      if (files == uids.size()) return dir;
      why = "it holds " + std::to_string(files) + " instance files where its .complete lists " +
            std::to_string(uids.size());
    }
    const fs::path moved = quarantineSeries(dir, why, options);
    std::cerr << "mvw: warning: the cached series " << seriesUid << " of " << server.text
              << " no longer verifies (" << why << "): moved into " << moved.string()
              << ", retrieving it again\n";
    return std::nullopt;
  };
  // Warm or cold, the same choice (issue 51): a series UID is read offline from a complete
  // cache; a number, modality or description is the server's to resolve whenever it answers (a
  // second series matching 'SEG' makes the choice ambiguous warm as cold).
  const bool byUid = isUid(selection) && selection.find('.') != std::string::npos;
  if (byUid)
    if (auto dir = completeFolder(selection)) return *dir;
  std::vector<Match> all;
  try {
    all = findSeries(server, studyUid, options);
  } catch (const ServiceError& e) {
    // Unreachable: the series this selection chose when the server last answered, said.
    std::ifstream in(selectionFile);
    std::string chosen;
    if (!byUid && in && std::getline(in, chosen) && isUid(chosen))
      if (auto dir = completeFolder(chosen)) {
        std::cerr << "mvw: warning: " << e.what() << "; series '" << selection << "' of study "
                  << studyUid << " is read from the cache as series " << chosen
                  << ", the one it named when the server last answered\n";
        return *dir;
      }
    throw;
  }
  const Match series = selectSeries(server, all, studyUid, selection);
  const std::string seriesUid = series.at("SeriesInstanceUID");
  if (!fs::exists(studyDir / seriesUid / ".complete") || !completeFolder(seriesUid)) {
    // The .partial folder survives an interruption; what it holds that verifies is kept.
    const fs::path partial = studyDir / (seriesUid + ".partial");
    fs::create_directories(partial);
    // Ctrl-C keeps it too, and says so (io/Interrupt.h): the next run resumes from it.
    const io::RemovedOnInterrupt resumable(fs::absolute(partial),
                                           io::RemovedOnInterrupt::Action::Keep);
    bool resuming = false;
    for (const auto& e : fs::directory_iterator(partial))
      if (e.path().extension() != ".dcm")
        fs::remove(e.path());
      else
        resuming = true;
    std::set<std::string> listed;
    const long stated = statedCount(series);
    // Every instance a Receiver accepts was parsed and its UIDs checked as it arrived: it is not
    // parsed again here. Those kept from an interrupted retrieve are (missingInstances).
    bool allReceivedNow = false;
    if (!resuming && stated > 0) {
      // A fresh retrieve: the whole series, complete when it holds as many verified instances
      // as the server states (the listing is needed only to resume).
      detail::Receiver receiver(server, partial, {studyUid, {seriesUid}}, options.progress);
      receiver.setOnProgress(options.onProgress);
      retrieve(server, studyUid, seriesUid, {}, receiver, options);
      receiver.report(true);
      for (const auto& e : fs::directory_iterator(partial))
        if (e.path().extension() == ".dcm") listed.insert(e.path().stem().string());
      if (static_cast<long>(listed.size()) != stated)
        throw ServiceError(server.text + ": the retrieve of series " + seriesUid + " ended with " +
                           std::to_string(listed.size()) + " of the " +
                           countOf(stated, "instance") + " it holds");
      allReceivedNow = true;
    } else {
      listed = instanceUids(findInstances(server, studyUid, seriesUid, options));
    }
    if (listed.empty())
      throw ServiceError(server.text + ": lists no instances in series " + seriesUid);
    std::vector<std::string> missing = allReceivedNow
                                           ? std::vector<std::string>{}
                                           : missingInstances(partial, listed, studyUid, seriesUid);
    if (!missing.empty()) {
      detail::Receiver receiver(server, partial, {studyUid, {seriesUid}}, options.progress);
      receiver.setOnProgress(options.onProgress);
      // Resuming a few: fetch those alone; otherwise the series in one request.
      const bool resume = missing.size() < listed.size();
      retrieve(server, studyUid, seriesUid, resume ? missing : std::vector<std::string>{}, receiver,
               options);
      receiver.report(true);
      missing = absentInstances(partial, listed);
      if (!missing.empty())
        throw ServiceError(server.text + ": the retrieve of series " + seriesUid + " ended with " +
                           std::to_string(missing.size()) + " of " +
                           countOf(static_cast<long long>(listed.size()), "instance") + " missing");
    }
    for (const auto& e : fs::directory_iterator(partial))
      if (e.path().extension() == ".dcm" &&
          !listed.count(e.path().stem().string()))  // an instance the server no longer lists
        fs::remove(e.path());
    {
      std::ofstream out(partial / ".complete.tmp");
      for (const std::string& uid : listed) out << uid << "\n";
      if (!out.flush()) throw Error("cannot write " + (partial / ".complete.tmp").string());
    }
    fs::rename(partial / ".complete.tmp", partial / ".complete");
    const fs::path final = studyDir / seriesUid;
    fs::remove_all(final);
    fs::rename(partial, final);
  }
  {
    const fs::path tmp = selectionFile.string() + ".tmp";
    std::ofstream(tmp) << seriesUid << "\n";
    fs::rename(tmp, selectionFile);
  }
  // Verified: complete as found (completeFolder), or each instance as it arrived and those
  // kept from an interrupted retrieve by missingInstances. The next read checks it all again.
  return studyDir / seriesUid;
}

fs::path detail::studyFolder(const Server& server, const std::string& studyUid,
                             const Options& options) {
  return cacheRoot(options) / serverKey(server) / studyUid;
}

fs::path quarantineRoot(const Options& options) { return cacheRoot(options) / "quarantine"; }

fs::path quarantineSeries(const fs::path& seriesDir, const std::string& why, const Options& options,
                          std::uint64_t limitBytes) {
  // Only <cache>/<server>/<study>/<series> moves: nothing outside the cache, no quarantine entry.
  const fs::path root = fs::absolute(cacheRoot(options)).lexically_normal();
  const fs::path dir = fs::absolute(seriesDir).lexically_normal();
  const fs::path rel = dir.lexically_relative(root);
  std::vector<std::string> parts;
  for (const fs::path& part : rel) parts.push_back(part.string());
  if (parts.size() != 3 || parts[0] == "quarantine" || parts[0] == ".." || !isUid(parts[1]) ||
      !isUid(parts[2]) || !fs::is_directory(dir))
    throw InputError(seriesDir, "is not a series folder of the PACS cache " + root.string());
  const fs::path qroot = quarantineRoot(options);
  fs::create_directories(qroot);
  // A name taken (the same series moved within the same microsecond) is made again with a later
  // stamp, never suffixed: a suffixed name, or one freed by the bound below and given again,
  // would not sort by age, and a later bound would drop a newer entry before an older one.
  fs::path target;
  do {
    target = qroot / (utcStamp() + "-" + parts[2]);
  } while (fs::exists(target));
  fs::rename(dir, target);
  {
    std::ofstream out(target / "why.txt");
    out << "server folder: " << parts[0] << "\nstudy: " << parts[1] << "\nseries: " << parts[2]
        << "\n"
        << why << "\n";
  }
  // Bounded: the oldest go first; the one just moved stays, whatever its size.
  std::vector<fs::path> entries = quarantined(qroot);
  std::vector<std::uint64_t> sizes;
  std::uint64_t total = 0;
  for (const fs::path& e : entries) total += sizes.emplace_back(treeBytes(e));
  for (std::size_t i = 0; i < entries.size() && total > limitBytes; ++i) {
    if (entries[i] == target) continue;
    std::error_code ec;
    fs::remove_all(entries[i], ec);
    if (!ec) total -= sizes[i];
  }
  return target;
}

QuarantineSize quarantineSize(const Options& options) {
  QuarantineSize size;
  for (const fs::path& e : quarantined(quarantineRoot(options))) {
    ++size.series;
    size.bytes += treeBytes(e);
  }
  return size;
}

QuarantineSize clearQuarantine(const Options& options) {
  QuarantineSize size;
  for (const fs::path& e : quarantined(quarantineRoot(options))) {
    const std::uint64_t bytes = treeBytes(e);
    fs::remove_all(e);
    ++size.series;
    size.bytes += bytes;
  }
  return size;
}

}  // namespace mvw::pacs
