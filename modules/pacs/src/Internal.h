#pragma once
// What the protocol halves (DicomWeb.cpp, Dimse.cpp) share with Pacs.cpp: one retrieve into a
// staging folder, the checks every received file passes, progress.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mvw/pacs/Pacs.h"

class DcmDataset;

namespace mvw::pacs::detail {

// An answer slower than this for --read-timeout seconds has stalled: over DICOMweb curl's
// low-speed limit (DicomWeb.cpp), over DIMSE within a message that has started (Dimse.cpp).
inline constexpr long kLowSpeedBytesPerSecond = 1024;

// The UIDs a received instance must carry; empty: any.
struct Expect {
  std::string studyUid;
  std::set<std::string> seriesUids;
};

// Instances as they arrive: each checked and written as <staging>/<SOPInstanceUID>.dcm.
class Receiver {
 public:
  Receiver(const Server& server, std::filesystem::path staging, Expect expect, bool progress);
  // Ends a progress line left open (by a retrieve that failed), so the error starts a line.
  ~Receiver();
  Receiver(const Receiver&) = delete;
  Receiver& operator=(const Receiver&) = delete;
  // A DICOM file received whole at `file` (a temporary name in the staging folder): parsed,
  // its UIDs checked, renamed to <SOPInstanceUID>.dcm. ServiceError naming the server when
  // the object is not what was asked for.
  void acceptFile(const std::filesystem::path& file);
  void addBytes(std::uint64_t n) { bytes_ += n; }
  // Told after each instance received (Options::onProgress).
  void setOnProgress(std::function<void(const Transfer&)> f) { onProgress_ = std::move(f); }
  // The progress line: on a terminal a running line rewritten by carriage returns (at most
  // twice a second), and with `final` the closing count ("pacs: 3 instances, 1.2 MB, ...").
  void report(bool final);
  // Wipes a running line without a closing count: for a caller that says what it received
  // itself (`mvw pacs get` prints transferSummary), so one final line says it.
  void clearLine();
  Transfer transfer() const;
  const std::filesystem::path& staging() const { return staging_; }
  int count() const { return static_cast<int>(received_.size()); }
  // The distinct instances received of one series.
  long countOf(const std::string& seriesUid) const {
    auto it = perSeries_.find(seriesUid);
    return it == perSeries_.end() ? 0 : it->second;
  }

 private:
  const Server& server_;
  std::filesystem::path staging_;
  Expect expect_;
  bool progress_;
  std::function<void(const Transfer&)> onProgress_;
  bool lineOpen_ = false;
  std::size_t lineLength_ = 0;  // of the running line, to wipe it
  std::set<std::string> received_;
  std::map<std::string, long> perSeries_;
  std::uint64_t bytes_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point lastReport_ = start_;
};

// The UIDs a DICOM file carries, or nullopt when it does not parse.
struct FileUids {
  std::string sopInstance;
  std::string series;
  std::string study;
};
std::optional<FileUids> readUids(const std::filesystem::path& file);

// What makes an instance count as received (issue 50), the one check a retrieve (Receiver) and
// the verified cache (cachedSeries) apply: the whole dataset parses; its native Pixel Data (or
// Float / Double Float Pixel Data) holds at least ceil(Rows x Columns x frames x samples x
// Bits Allocated / 8) bytes (two samples a pixel for YBR_*_422), or, encapsulated, every
// frame's fragments and the sequence delimiter are present (as many fragments as frames at
// least; a Basic Offset Table, when there is one, points at a fragment for each frame); it
// carries a SOP Instance UID. The UIDs asked for are the caller's to compare.
struct InstanceCheck {
  std::optional<FileUids> uids;  // nullopt: `problem` says why
  std::string problem;           // empty: the instance counts
  bool ok() const { return uids.has_value() && problem.empty(); }
};
InstanceCheck checkInstance(const std::filesystem::path& file);

// The instances of `seriesUid` (all of them, or only `instances`) retrieved into `receiver`.
void webRetrieve(const Server& server, const std::string& studyUid, const std::string& seriesUid,
                 const std::vector<std::string>& instances, Receiver& receiver,
                 const Options& options);
void dimseRetrieve(const Server& server, const std::string& studyUid, const std::string& seriesUid,
                   const std::vector<std::string>& instances, Receiver& receiver,
                   const Options& options);

double webEcho(const Server& server, const Options& options);
double dimseEcho(const Server& server, const Options& options);
// level: STUDY, SERIES or IMAGE; keys: keyword -> value (empty: return it).
std::vector<Match> webFind(const Server& server, const std::string& level, const Match& keys,
                           const Options& options);
std::vector<Match> dimseFind(const Server& server, const std::string& level, const Match& keys,
                             const Options& options);
// A QIDO-RS answer's body (DICOM JSON) as matches: the keywords DCMTK's dictionary knows, each
// value as text; the UIDs of the request path (`inPath`, their values from `keys`) added where
// the answer leaves them out. ServiceError naming `serverText` for anything but an array of
// DICOM JSON objects keyed by tags. Its own function for tests/fuzz/fuzz_qido.cpp.
std::vector<Match> parseQidoAnswer(const std::string& serverText, const std::string& body,
                                   const std::set<std::string>& inPath, const Match& keys);
// One C-FIND response's identifier as a match: every element but sequences and
// QueryRetrieveLevel, by keyword, its values as text. For tests/fuzz/fuzz_cfind.cpp too.
Match matchFromIdentifier(DcmDataset& identifier);
void webStore(const Server& server, const std::vector<std::filesystem::path>& files,
              const Options& options);
void dimseStore(const Server& server, const std::vector<std::filesystem::path>& files,
                const Options& options);

// The cache folder of one study of one server: <cacheRoot>/<server key>/<studyUid>, holding a
// folder per series (<seriesUid>, complete when it holds .complete) and the series each
// selection chose (selection-<hex of the selection>).
std::filesystem::path studyFolder(const Server& server, const std::string& studyUid,
                                  const Options& options);

// DCMTK logs to stderr by default; mvw says what went wrong itself, once. Called before any
// DCMTK work.
void quietDcmtk();

// A QIDO-RS query value as sent: the wildcards '*' and '?' and the name separator '^' as they
// are (servers such as Orthanc 1.10 match only the raw characters; RFC 3986 allows '*' and
// '?' in a query), percent-encoded where the character would change the query ('&', '=', '+',
// '#', '%', space, controls, bytes above 0x7F).
std::string queryValue(const std::string& text);

// The DICOM keyword of tag (group, element) from DCMTK's dictionary, "" when unknown.
std::string keywordOf(unsigned group, unsigned element);

}  // namespace mvw::pacs::detail
