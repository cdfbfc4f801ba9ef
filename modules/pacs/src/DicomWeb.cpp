// DICOMweb with libcurl: QIDO-RS (find, echo), WADO-RS (retrieve: the multipart/related answer
// parsed here, strictly bounded), STOW-RS (store).
#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>

#include <curl/curl.h>
#include <nlohmann/json.hpp>

#include "Internal.h"
#include "Multipart.h"
#include "mvw/core/Error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace mvw::pacs::detail {

namespace {

// Bounds on what a server may send: a query answer, a retrieve (its parts, their headers:
// MultipartLimits), the matches of a query, an error answer kept for its message.
constexpr std::size_t kMaxQueryBytes = 64u << 20;
constexpr std::size_t kMaxRetrieveBytes = std::size_t{4} << 30;
constexpr std::size_t kMaxMatches = 100000;
constexpr std::size_t kMaxErrorBodyBytes = 64u << 10;

struct Credentials {
  std::string user, password;
};

// MVW_PACS_USER and MVW_PACS_PASSWORD, or MVW_PACS_CREDENTIALS naming a file "user:password"
// that only its owner can read. Never from the command line; never printed.
std::optional<Credentials> credentials() {
  const char* user = std::getenv("MVW_PACS_USER");
  const char* password = std::getenv("MVW_PACS_PASSWORD");
  if (user && *user) return Credentials{user, password ? password : ""};
  const char* file = std::getenv("MVW_PACS_CREDENTIALS");
  if (!file || !*file) return std::nullopt;
  requireReadable(file);
  struct stat st {};
  if (::stat(file, &st) != 0 || st.st_uid != ::getuid() || (st.st_mode & 077) != 0)
    throw InputError(file,
                     "holds credentials but others can read it or it is not yours: chmod 600 it");
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto colon = line.find(':');
  if (colon == std::string::npos || colon == 0)
    throw InputError(file, "must hold one line user:password");
  return Credentials{line.substr(0, colon), line.substr(colon + 1)};
}

// libcurl, loaded on first use: only `mvw pacs` and `--store` reach a DICOMweb server, and
// linked, libcurl brings 20 shared libraries of its own (TLS, LDAP, SSH, IDN...) that every
// start of mvw would load and relocate (docs/performance-log.md#start-up). The types come
// from <curl/curl.h>; the library is the one of the same ABI (soname libcurl.so.4).
struct CurlLibrary {
  decltype(&curl_global_init) globalInit = nullptr;
  decltype(&curl_easy_init) easyInit = nullptr;
  decltype(&curl_easy_cleanup) easyCleanup = nullptr;
  decltype(&curl_easy_setopt) easySetopt = nullptr;
  decltype(&curl_easy_perform) easyPerform = nullptr;
  decltype(&curl_easy_getinfo) easyGetinfo = nullptr;
  decltype(&curl_easy_strerror) easyStrerror = nullptr;
  decltype(&curl_slist_append) slistAppend = nullptr;
  decltype(&curl_slist_free_all) slistFreeAll = nullptr;
};

template <typename F>
void bind(void* handle, F& f, const char* name) {
  f = reinterpret_cast<F>(::dlsym(handle, name));
  if (!f) throw Error(std::string("libcurl.so.4 has no ") + name);
}

// Loaded once per process, initialised (curl_global_init) and never unloaded.
const CurlLibrary& curl() {
  static const CurlLibrary lib = [] {
    void* h = ::dlopen("libcurl.so.4", RTLD_NOW | RTLD_LOCAL);
    if (!h) {
      const char* why = ::dlerror();
      throw Error(std::string("cannot load libcurl.so.4 (DICOMweb): ") + (why ? why : "?"));
    }
    CurlLibrary l;
    bind(h, l.globalInit, "curl_global_init");
    bind(h, l.easyInit, "curl_easy_init");
    bind(h, l.easyCleanup, "curl_easy_cleanup");
    bind(h, l.easySetopt, "curl_easy_setopt");
    bind(h, l.easyPerform, "curl_easy_perform");
    bind(h, l.easyGetinfo, "curl_easy_getinfo");
    bind(h, l.easyStrerror, "curl_easy_strerror");
    bind(h, l.slistAppend, "curl_slist_append");
    bind(h, l.slistFreeAll, "curl_slist_free_all");
    l.globalInit(CURL_GLOBAL_DEFAULT);
    return l;
  }();
  return lib;
}

// A libcurl easy handle, cleaned up with the loaded library's function.
struct Easy {
  CURL* c = curl().easyInit();
  Easy() = default;
  Easy(const Easy&) = delete;
  Easy& operator=(const Easy&) = delete;
  ~Easy() {
    if (c) curl().easyCleanup(c);
  }
};

struct Response {
  long status = 0;
  std::string contentType;
  std::string body;
};

// Where the body of a successful (2xx) answer goes while it arrives, instead of into memory:
// the bytes and the answer's Content-Type. Throwing ends the transfer; request() rethrows.
using BodyStream = std::function<void(const char* bytes, std::size_t n, const std::string& type)>;

struct Sink {
  std::string* body = nullptr;
  std::size_t limit = 0;
  bool overflow = false;
  CURL* curl = nullptr;
  const BodyStream* stream = nullptr;
  int streaming = -1;  // with a stream: -1 not known yet, 1 a 2xx answer, 0 an error answer
  std::string contentType;
  std::uint64_t total = 0;
  std::exception_ptr error;  // thrown by the stream: nothing may unwind through libcurl
};

std::size_t writeBody(char* data, std::size_t size, std::size_t n, void* user) {
  auto* sink = static_cast<Sink*>(user);
  const std::size_t bytes = size * n;
  sink->total += bytes;
  if (sink->total > sink->limit) {
    sink->overflow = true;
    return 0;
  }
  if (sink->stream) {
    if (sink->streaming < 0) {  // the headers are in: the status and the type are known
      long status = 0;
      char* type = nullptr;
      curl().easyGetinfo(sink->curl, CURLINFO_RESPONSE_CODE, &status);
      curl().easyGetinfo(sink->curl, CURLINFO_CONTENT_TYPE, &type);
      sink->streaming = status >= 200 && status < 300 ? 1 : 0;
      if (type) sink->contentType = type;
    }
    if (sink->streaming == 0) {  // an error answer: its start, for the message
      if (sink->body->size() < kMaxErrorBodyBytes)
        sink->body->append(data, std::min(bytes, kMaxErrorBodyBytes - sink->body->size()));
      return bytes;
    }
    try {
      (*sink->stream)(data, bytes, sink->contentType);
    } catch (...) {
      sink->error = std::current_exception();
      return 0;
    }
    return bytes;
  }
  sink->body->append(data, bytes);
  return bytes;
}

std::string reason(long status) {
  switch (status) {
    case 400:
      return "Bad Request";
    case 401:
      return "Unauthorized (check MVW_PACS_USER and MVW_PACS_PASSWORD)";
    case 403:
      return "Forbidden";
    case 404:
      return "Not Found";
    case 406:
      return "Not Acceptable";
    case 500:
      return "Internal Server Error";
    case 503:
      return "Service Unavailable";
    default:
      return "";
  }
}

// What to check when a server's own API, not its DICOMweb root, answered (issue 51).
const char* const kCheckRoot =
    " (check that the URL is the server's DICOMweb root, the path before /studies: Orthanc's is "
    "http://host:port/dicom-web)";

Response request(const Server& server, const std::string& url, const std::string& accept,
                 std::size_t limit, const Options& options, const std::string* postBody = nullptr,
                 const std::string& postType = "", const BodyStream* stream = nullptr) {
  const CurlLibrary& lib = curl();
  Easy easy;
  if (!easy.c) throw Error("curl_easy_init failed");
  CURL* c = easy.c;
  Response r;
  Sink sink;
  sink.body = &r.body;
  sink.limit = limit;
  sink.curl = c;
  sink.stream = stream;
  char errors[CURL_ERROR_SIZE] = {0};
  curl_slist* headers = nullptr;
  headers = lib.slistAppend(headers, ("Accept: " + accept).c_str());
  if (postBody) headers = lib.slistAppend(headers, ("Content-Type: " + postType).c_str());
  std::unique_ptr<curl_slist, void (*)(curl_slist*)> headerGuard(headers, lib.slistFreeAll);
  lib.easySetopt(c, CURLOPT_URL, url.c_str());
  lib.easySetopt(c, CURLOPT_HTTPHEADER, headers);
  lib.easySetopt(c, CURLOPT_WRITEFUNCTION, writeBody);
  lib.easySetopt(c, CURLOPT_WRITEDATA, &sink);
  lib.easySetopt(c, CURLOPT_ERRORBUFFER, errors);
  lib.easySetopt(c, CURLOPT_NOSIGNAL, 1L);
  lib.easySetopt(c, CURLOPT_PROTOCOLS_STR, "http,https");
  lib.easySetopt(c, CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(options.connectTimeoutS * 1000.0));
  // The read time-out: less than 1 kB a second for this long ends the transfer. At 1 byte a
  // second (curl's usual floor) a server that trickles a byte or two a second held mvw forever
  // (issue 50's fault suite, tests/faults).
  lib.easySetopt(c, CURLOPT_LOW_SPEED_LIMIT, kLowSpeedBytesPerSecond);
  lib.easySetopt(c, CURLOPT_LOW_SPEED_TIME,
                 std::max(1L, static_cast<long>(options.readTimeoutS + 0.5)));
  lib.easySetopt(c, CURLOPT_ACCEPT_ENCODING, "");
  if (options.insecure) {
    lib.easySetopt(c, CURLOPT_SSL_VERIFYPEER, 0L);
    lib.easySetopt(c, CURLOPT_SSL_VERIFYHOST, 0L);
  }
  if (auto cred = credentials()) {
    lib.easySetopt(c, CURLOPT_HTTPAUTH, CURLAUTH_BASIC);
    lib.easySetopt(c, CURLOPT_USERNAME, cred->user.c_str());
    lib.easySetopt(c, CURLOPT_PASSWORD, cred->password.c_str());
  }
  if (postBody) {
    lib.easySetopt(c, CURLOPT_POST, 1L);
    lib.easySetopt(c, CURLOPT_POSTFIELDS, postBody->data());
    lib.easySetopt(c, CURLOPT_POSTFIELDSIZE_LARGE, static_cast<curl_off_t>(postBody->size()));
  }
  if (stream) lib.easySetopt(c, CURLOPT_BUFFERSIZE, 256L << 10);  // fewer, larger slices
  const CURLcode code = lib.easyPerform(c);
  if (sink.error) std::rethrow_exception(sink.error);
  if (sink.overflow)
    throw ServiceError(server.text + ": the answer exceeds " + std::to_string(limit >> 20) + " MB");
  if (code != CURLE_OK)
    throw ServiceError(server.text + ": " + lib.easyStrerror(code) +
                       (errors[0] ? std::string(" (") + errors + ")" : std::string()));
  lib.easyGetinfo(c, CURLINFO_RESPONSE_CODE, &r.status);
  char* type = nullptr;
  lib.easyGetinfo(c, CURLINFO_CONTENT_TYPE, &type);
  if (type) r.contentType = type;
  if (r.status >= 300) {
    const std::string said = printable(r.body, 200);
    // A study-level search every DICOMweb server answers: refused, the URL is likely not its
    // root (Orthanc's own API answers /studies?limit=1 with HTTP 400).
    const std::string studies = server.baseUrl + "/studies";
    const bool studyQuery = url.compare(0, studies.size(), studies) == 0 &&
                            (url.size() == studies.size() || url[studies.size()] == '?');
    throw ServiceError(server.text + ": HTTP " + std::to_string(r.status) + " " + reason(r.status) +
                       ((r.status == 400 || r.status == 404) && studyQuery ? kCheckRoot : "") +
                       (said.empty() ? "" : ": " + said));
  }
  return r;
}

void warnInsecure(const Server& server, const Options& options) {
  static bool said = false;
  if (options.insecure && !said && server.baseUrl.rfind("https", 0) == 0) {
    std::cerr << "mvw: warning: --insecure: the certificate of " << server.text
              << " is not verified\n";
    said = true;
  }
}

// One value of the DICOM JSON model as text; several joined by '\'.
std::string valueText(const json& element) {
  if (!element.is_object() || !element.contains("Value")) return "";
  const json& values = element["Value"];
  if (!values.is_array()) return "";
  std::string out;
  for (const json& v : values) {
    if (!out.empty()) out += "\\";
    if (v.is_string())
      out += v.get<std::string>();
    else if (v.is_number_integer())
      out += std::to_string(v.get<long long>());
    else if (v.is_number())
      out += std::to_string(v.get<double>());
    else if (v.is_object() && v.contains("Alphabetic") && v["Alphabetic"].is_string())
      out += v["Alphabetic"].get<std::string>();
  }
  return out;
}

// A server's own REST API answers /studies with a JSON array of its ids (Orthanc at
// http://host:8042 rather than http://host:8042/dicom-web): what to check (issue 51).
[[noreturn]] void notDicomJsonObject(const Server& server) {
  throw ServiceError(server.text + ": answered a match that is not a DICOM JSON object" +
                     kCheckRoot);
}

}  // namespace

double webEcho(const Server& server, const Options& options) {
  warnInsecure(server, options);
  const auto start = std::chrono::steady_clock::now();
  Response r = request(server, server.baseUrl + "/studies?limit=1", "application/dicom+json",
                       kMaxQueryBytes, options);
  if (r.status != 204 && !r.body.empty() && !json::accept(r.body))
    throw ServiceError(server.text +
                       ": answered the QIDO-RS request with something that is not "
                       "DICOM JSON");
  if (r.status != 204 && !r.body.empty()) {
    const json answer = json::parse(r.body, nullptr, false);
    if (answer.is_array() && !answer.empty() && !answer.front().is_object())
      notDicomJsonObject(server);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<Match> webFind(const Server& server, const std::string& level, const Match& keys,
                           const Options& options) {
  warnInsecure(server, options);
  auto key = [&](const char* k) { return matchValue(keys, k); };
  std::string url = server.baseUrl;
  std::set<std::string> inPath;
  if (level == "STUDY") {
    url += "/studies";
  } else if (level == "SERIES") {
    url += "/studies/" + key("StudyInstanceUID") + "/series";
    inPath = {"StudyInstanceUID"};
  } else {
    url += "/studies/" + key("StudyInstanceUID") + "/series/" + key("SeriesInstanceUID") +
           "/instances";
    inPath = {"StudyInstanceUID", "SeriesInstanceUID"};
  }
  std::string query;
  for (const auto& [k, v] : keys) {
    if (inPath.count(k)) continue;
    query += query.empty() ? "?" : "&";
    query += v.empty() ? "includefield=" + k : k + "=" + queryValue(v);
  }
  Response r = request(server, url + query, "application/dicom+json", kMaxQueryBytes, options);
  if (r.status == 204) return {};
  return parseQidoAnswer(server.text, r.body, inPath, keys);
}

std::vector<Match> parseQidoAnswer(const std::string& serverText, const std::string& body,
                                   const std::set<std::string>& inPath, const Match& keys) {
  std::vector<Match> matches;
  if (body.empty()) return matches;
  json answer = json::parse(body, nullptr, false);
  if (answer.is_discarded() || !answer.is_array())
    throw ServiceError(serverText +
                       ": answered the QIDO-RS request with something that is not "
                       "a DICOM JSON array: '" +
                       printable(body, 60) + "'");
  if (answer.size() > kMaxMatches)
    throw ServiceError(serverText + ": answered more than " + std::to_string(kMaxMatches) +
                       " matches");
  for (const json& object : answer) {
    if (!object.is_object())
      throw ServiceError(serverText + ": answered a match that is not a DICOM JSON object" +
                         kCheckRoot);
    Match m;
    for (const auto& [tag, element] : object.items()) {
      if (tag.size() != 8 || tag.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
        throw ServiceError(serverText + ": answered a DICOM JSON key that is not a tag: '" +
                           printable(tag, 20) + "'");
      const unsigned long t = std::stoul(tag, nullptr, 16);
      const std::string keyword = keywordOf(t >> 16, t & 0xffff);
      if (!keyword.empty()) m[keyword] = valueText(element);
    }
    // The path's UIDs belong to the match as well (Orthanc repeats them; others may not).
    for (const std::string& k : inPath)
      if (!m.count(k)) m[k] = matchValue(keys, k.c_str());
    matches.push_back(std::move(m));
  }
  return matches;
}

namespace {

// Each part of a WADO-RS answer written to <staging>/.part-N while it arrives, and handed to the
// receiver (parsed, its UIDs checked, renamed to <SOPInstanceUID>.dcm) as soon as it ends. A
// part left unfinished (the answer broke off) is removed.
class PartFiles : public MultipartSink {
 public:
  explicit PartFiles(Receiver& receiver) : receiver_(receiver) {}
  ~PartFiles() override {
    if (file_) {
      std::fclose(file_);
      std::error_code ec;
      fs::remove(path_, ec);
    }
  }
  PartFiles(const PartFiles&) = delete;
  PartFiles& operator=(const PartFiles&) = delete;

  void begin(std::size_t index) override {
    path_ = receiver_.staging() / (".part-" + std::to_string(index));
    file_ = std::fopen(path_.c_str(), "wb");
    if (!file_) throw Error("cannot write " + path_.string());
  }
  void data(const char* bytes, std::size_t n) override {
    if (std::fwrite(bytes, 1, n, file_) != n) throw Error("cannot write " + path_.string());
  }
  void end() override {
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) throw Error("cannot write " + path_.string());
    receiver_.acceptFile(path_);
  }

 private:
  Receiver& receiver_;
  fs::path path_;
  std::FILE* file_ = nullptr;
};

// One WADO-RS request, its multipart/related answer parsed while it downloads.
void retrieveMultipart(const Server& server, const std::string& url, Receiver& receiver,
                       const Options& options) {
  const std::string accept = "multipart/related; type=\"application/dicom\"; transfer-syntax=*";
  PartFiles files(receiver);
  std::optional<MultipartParser> parser;
  const BodyStream stream = [&](const char* bytes, std::size_t n, const std::string& type) {
    if (!parser) parser.emplace(multipartBoundary(type), files);
    parser->feed(bytes, n);
  };
  // A broken answer is the server's failure, named as such (the stream's exception comes back
  // out of request(), which rethrows it after the transfer).
  try {
    const Response r =
        request(server, url, accept, kMaxRetrieveBytes, options, nullptr, "", &stream);
    if (!parser) parser.emplace(multipartBoundary(r.contentType), files);  // an empty answer
    parser->finish();
  } catch (const MultipartError& e) {
    throw ServiceError(server.text + ": " + e.what());
  }
}

}  // namespace

void webRetrieve(const Server& server, const std::string& studyUid, const std::string& seriesUid,
                 const std::vector<std::string>& instances, Receiver& receiver,
                 const Options& options) {
  warnInsecure(server, options);
  const std::string series = server.baseUrl + "/studies/" + studyUid + "/series/" + seriesUid;
  std::vector<std::string> urls;
  if (instances.empty())
    urls.push_back(series);
  else
    for (const std::string& uid : instances) urls.push_back(series + "/instances/" + uid);
  for (const std::string& url : urls) retrieveMultipart(server, url, receiver, options);
}

void webStore(const Server& server, const std::vector<fs::path>& files, const Options& options) {
  warnInsecure(server, options);
  const std::string boundary = "mvw-stow-boundary-8f2c1d";
  // In batches of about 64 MB, each one STOW-RS request.
  std::size_t i = 0;
  while (i < files.size()) {
    std::string body;
    std::size_t inBatch = 0;
    while (i < files.size() && (inBatch == 0 || body.size() < (64u << 20))) {
      std::ifstream in(files[i], std::ios::binary);
      std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (!in && !in.eof()) throw InputError(files[i], "cannot be read");
      body += "--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n";
      body += data;
      body += "\r\n";
      ++i;
      ++inBatch;
    }
    body += "--" + boundary + "--\r\n";
    Response r = request(server, server.baseUrl + "/studies", "application/dicom+json",
                         kMaxQueryBytes, options, &body,
                         "multipart/related; type=\"application/dicom\"; boundary=" + boundary);
    json answer = json::parse(r.body, nullptr, false);
    // FailedSOPSequence (0008,1198): the instances the server refused.
    if (answer.is_object() && answer.contains("00081198") && !valueText(answer["00081198"]).empty())
      throw ServiceError(server.text +
                         ": refused some of the instances stored (STOW-RS "
                         "FailedSOPSequence)");
    if (answer.is_object() && answer.contains("00081198") && answer["00081198"].contains("Value") &&
        !answer["00081198"]["Value"].empty())
      throw ServiceError(server.text + ": refused " +
                         std::to_string(answer["00081198"]["Value"].size()) +
                         " of the instances stored (STOW-RS FailedSOPSequence)");
  }
}

std::string queryValue(const std::string& text) {
  // RFC 3986 lets a query hold unreserved characters, sub-delimiters, ':', '@', '/' and '?'
  // as they are. '&', '=', '+' and '#' would end or change the value, and '%' starts an escape.
  // '^' (the PN component separator) is not in RFC 3986's sets, but every HTTP stack mvw
  // meets passes it through, and Orthanc 1.10 matches only the raw character.
  static const std::string keep = "-._~!$'()*,;:@/?^";
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (const unsigned char c : text) {
    if ((c < 0x80 && std::isalnum(c)) || keep.find(static_cast<char>(c)) != std::string::npos) {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

}  // namespace mvw::pacs::detail
