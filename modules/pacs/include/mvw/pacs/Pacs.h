#pragma once
// Studies from a PACS (issue 37): query and retrieve over DICOMweb (QIDO-RS, WADO-RS, STOW-RS)
// and DIMSE (C-ECHO, C-FIND, C-GET, C-MOVE, C-STORE), into a folder or the verified cache.
// DCMTK and libcurl stay inside this module's .cpp files.
//
// A server's answer is input: UIDs are checked (isUid) before one names a file, sizes and
// counts are bounded. A server that cannot be reached, refuses or breaks off is a ServiceError
// naming the server and what it said (never credentials); bad input is an InputError.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mvw/pacs/StoreFiles.h"

namespace mvw::pacs {

enum class Protocol { DicomWeb, Dimse };

// SERVER as the user writes it: http(s)://host:port/PATH (DICOMweb) or dicom://AET@host:port.
struct Server {
  Protocol protocol = Protocol::DicomWeb;
  std::string text;     // as given (never holds credentials: parseServer refuses them)
  std::string baseUrl;  // DICOMweb: the URL without a trailing slash
  std::string host;     // DIMSE
  int port = 0;         // DIMSE
  std::string calledAet;
};

// Throws InputError (naming SERVER) for anything else, and for credentials in a URL.
Server parseServer(const std::string& text);

// What a retrieve or a store moved, and in how long.
struct Transfer {
  int instances = 0;
  std::uint64_t bytes = 0;
  double seconds = 0.0;
};

// How one call reaches the server and where the cache is. Each call is given its own: a study
// read takes them from its caller (study::localPath, study::Session::load), never from
// process-wide state.
struct Options {
  std::string callingAet = "MVW";
  double connectTimeoutS = 10.0;
  double readTimeoutS = 60.0;
  bool insecure = false;  // HTTPS without certificate verification (said on stderr)
  // DIMSE retrieve by C-MOVE to this AE title, received by mvw's own storage SCP on movePort;
  // empty: C-GET.
  std::string moveToAet;
  int movePort = 0;
  bool progress = true;  // instances and MB/s on stderr
  // Called (on the retrieving thread) after each instance a retrieve receives with what it has
  // received so far (the viewer's PACS window shows it); empty: none.
  std::function<void(const Transfer&)> onProgress;
  // The verified cache (cachedSeries); empty: $XDG_CACHE_HOME/mvw/dicom or ~/.cache/mvw/dicom.
  std::filesystem::path cacheDir;
};

// The cache folder Options::cacheDir names, or the default.
std::filesystem::path cacheRoot(const Options& options);

// A DICOM UID: 1..64 characters, digits and dots, no empty component. Only such a string ever
// names a file.
bool isUid(const std::string& text);

// A DICOM AE title as mvw accepts one (--calling-aet, servers.json's calling_aet): 1..16
// characters.
bool isAeTitle(const std::string& text);

// One query match keyed by DICOM keyword (StudyInstanceUID, Modality, ...); several values
// joined by '\'.
using Match = std::map<std::string, std::string>;

// The value of KEYWORD in a match; empty when the server did not send it.
std::string matchValue(const Match& match, const char* keyword);

struct StudyQuery {
  std::string patientId;
  std::string patientName;  // DICOM wildcards * and ?
  std::string studyDate;    // YYYYMMDD, or a range YYYYMMDD-YYYYMMDD
  std::string modality;
  std::string accession;
  std::string studyUid;
};

// The round trip of a C-ECHO or a QIDO-RS request, in seconds.
double echo(const Server& server, const Options& options);
std::vector<Match> findStudies(const Server& server, const StudyQuery& query,
                               const Options& options);
std::vector<Match> findSeries(const Server& server, const std::string& studyUid,
                              const Options& options);
// findSeries, and where the server lists none, whether it has the study at all: InputError
// naming the server when it has no such study (`mvw pacs find --study`, mvw.pacs.find).
std::vector<Match> findStudySeries(const Server& server, const std::string& studyUid,
                                   const Options& options);
std::vector<Match> findInstances(const Server& server, const std::string& studyUid,
                                 const std::string& seriesUid, const Options& options);

// The series of a study one selection names: its UID, its number, its modality or part of its
// description (case-insensitive). InputError when none or several match.
Match selectSeries(const Server& server, const std::vector<Match>& series,
                   const std::string& studyUid, const std::string& selection);

// Every instance of the chosen series (all series of the study when `series` is empty) into
// `outDir`, one file per instance named <SOPInstanceUID>.dcm. Staged in a hidden folder inside
// outDir and moved in when all are verified; nothing is left on failure. Progress (a running
// line on a terminal) ends without a closing count: the caller prints what it returns
// (transferSummary).
Transfer get(const Server& server, const std::string& studyUid,
             const std::vector<std::string>& series, const std::filesystem::path& outDir,
             const Options& options);

// The files (and every DICOM file under each folder: storeFiles) sent to the server: STOW-RS or
// C-STORE. InputError for a file named that is not DICOM, ServiceError when the server refuses
// one.
Transfer store(const Server& server, const std::vector<std::filesystem::path>& files,
               const Options& options);
// Those storeFiles chose (the caller says what it skipped).
Transfer store(const Server& server, const StoreFiles& chosen, const Options& options);

// The folder in the verified cache holding the series `selection` of study `studyUid`,
// retrieved first unless it is there complete and verified: every instance the server has (as
// many as it states for the series, or every one it lists), each whole (the dataset parses, the
// Pixel Data holds every frame's bytes or fragments) and carrying the SOP Instance, series and
// study UIDs asked for. An interrupted retrieve leaves only a .partial folder, which the next
// call resumes. A cached series that no longer verifies is moved into the quarantine (said on
// stderr) and retrieved again.
//
// Warm or cold, the same series is chosen: a selection that is a series UID (it has a dot) is
// read from a complete cache without asking the server; one by number, modality or description
// is resolved by the server whenever it answers, and only when it cannot be reached is the
// series it chose last time read from the cache, with a warning naming that series' UID.
std::filesystem::path cachedSeries(const Server& server, const std::string& studyUid,
                                   const std::string& selection, const Options& options);

// The cache's quarantine: series whose files failed to read after they were cached, kept for
// a look and never read again. At most kQuarantineBytes: the oldest are dropped beyond it (the
// newest is always kept). `mvw pacs cache --clear-quarantine` empties it.
inline constexpr std::uint64_t kQuarantineBytes = std::uint64_t{1} << 30;
std::filesystem::path quarantineRoot(const Options& options);

// Moves `seriesDir` (a series folder cachedSeries returned) into the quarantine, with a file
// why.txt holding `why`, so the next cachedSeries retrieves it again; returns where it went.
// InputError when `seriesDir` is not a series folder of the cache.
std::filesystem::path quarantineSeries(const std::filesystem::path& seriesDir,
                                       const std::string& why, const Options& options,
                                       std::uint64_t limitBytes = kQuarantineBytes);

// What the quarantine holds, or held before clearQuarantine emptied it.
struct QuarantineSize {
  int series = 0;
  std::uint64_t bytes = 0;
};
QuarantineSize quarantineSize(const Options& options);
QuarantineSize clearQuarantine(const Options& options);

}  // namespace mvw::pacs
