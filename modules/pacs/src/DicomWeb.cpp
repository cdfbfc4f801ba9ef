// DICOMweb with libcurl: QIDO-RS (find, echo), WADO-RS (retrieve: the multipart/related answer
// parsed here, strictly bounded), STOW-RS (store).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <string_view>

#include <curl/curl.h>
#include <nlohmann/json.hpp>

#include "Internal.h"
#include "mvw/core/Error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace mvw::pacs::detail {

namespace {

// Bounds on what a server may send: a query answer, a retrieve, one part's headers, the parts.
constexpr std::size_t kMaxQueryBytes = 64u << 20;
constexpr std::size_t kMaxRetrieveBytes = std::size_t{4} << 30;
constexpr std::size_t kMaxPartHeaderBytes = 16u << 10;
constexpr std::size_t kMaxParts = 100000;
constexpr std::size_t kMaxMatches = 100000;

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

void curlInit() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

struct Response {
  long status = 0;
  std::string contentType;
  std::string body;
};

struct Sink {
  std::string* body;
  std::size_t limit;
  bool overflow = false;
};

std::size_t writeBody(char* data, std::size_t size, std::size_t n, void* user) {
  auto* sink = static_cast<Sink*>(user);
  const std::size_t bytes = size * n;
  if (sink->body->size() + bytes > sink->limit) {
    sink->overflow = true;
    return 0;
  }
  sink->body->append(data, bytes);
  return bytes;
}

std::string printable(const std::string& text, std::size_t max) {
  std::string out;
  for (char c : text.substr(0, max)) out += (c >= 32 && c < 127) ? c : ' ';
  return out;
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

Response request(const Server& server, const std::string& url, const std::string& accept,
                 std::size_t limit, const Options& options, const std::string* postBody = nullptr,
                 const std::string& postType = "") {
  curlInit();
  std::unique_ptr<CURL, void (*)(CURL*)> curl(curl_easy_init(), curl_easy_cleanup);
  if (!curl) throw Error("curl_easy_init failed");
  CURL* c = curl.get();
  Response r;
  Sink sink{&r.body, limit};
  char errors[CURL_ERROR_SIZE] = {0};
  curl_slist* headers = nullptr;
  headers = curl_slist_append(headers, ("Accept: " + accept).c_str());
  if (postBody) headers = curl_slist_append(headers, ("Content-Type: " + postType).c_str());
  std::unique_ptr<curl_slist, void (*)(curl_slist*)> headerGuard(headers, curl_slist_free_all);
  curl_easy_setopt(c, CURLOPT_URL, url.c_str());
  curl_easy_setopt(c, CURLOPT_HTTPHEADER, headers);
  curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, writeBody);
  curl_easy_setopt(c, CURLOPT_WRITEDATA, &sink);
  curl_easy_setopt(c, CURLOPT_ERRORBUFFER, errors);
  curl_easy_setopt(c, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(c, CURLOPT_PROTOCOLS_STR, "http,https");
  curl_easy_setopt(c, CURLOPT_CONNECTTIMEOUT_MS,
                   static_cast<long>(options.connectTimeoutS * 1000.0));
  // The read time-out: no byte for this long ends the transfer.
  curl_easy_setopt(c, CURLOPT_LOW_SPEED_LIMIT, 1L);
  curl_easy_setopt(c, CURLOPT_LOW_SPEED_TIME,
                   std::max(1L, static_cast<long>(options.readTimeoutS + 0.5)));
  curl_easy_setopt(c, CURLOPT_ACCEPT_ENCODING, "");
  if (options.insecure) {
    curl_easy_setopt(c, CURLOPT_SSL_VERIFYPEER, 0L);
    curl_easy_setopt(c, CURLOPT_SSL_VERIFYHOST, 0L);
  }
  if (auto cred = credentials()) {
    curl_easy_setopt(c, CURLOPT_HTTPAUTH, CURLAUTH_BASIC);
    curl_easy_setopt(c, CURLOPT_USERNAME, cred->user.c_str());
    curl_easy_setopt(c, CURLOPT_PASSWORD, cred->password.c_str());
  }
  if (postBody) {
    curl_easy_setopt(c, CURLOPT_POST, 1L);
    curl_easy_setopt(c, CURLOPT_POSTFIELDS, postBody->data());
    curl_easy_setopt(c, CURLOPT_POSTFIELDSIZE_LARGE, static_cast<curl_off_t>(postBody->size()));
  }
  const CURLcode code = curl_easy_perform(c);
  if (sink.overflow)
    throw ServiceError(server.text + ": the answer exceeds " + std::to_string(limit >> 20) + " MB");
  if (code != CURLE_OK)
    throw ServiceError(server.text + ": " + curl_easy_strerror(code) +
                       (errors[0] ? std::string(" (") + errors + ")" : std::string()));
  curl_easy_getinfo(c, CURLINFO_RESPONSE_CODE, &r.status);
  char* type = nullptr;
  curl_easy_getinfo(c, CURLINFO_CONTENT_TYPE, &type);
  if (type) r.contentType = type;
  if (r.status >= 300) {
    const std::string said = printable(r.body, 200);
    throw ServiceError(server.text + ": HTTP " + std::to_string(r.status) + " " + reason(r.status) +
                       (said.empty() ? "" : ": " + said));
  }
  return r;
}

std::string escape(const std::string& text) {
  curlInit();
  std::unique_ptr<CURL, void (*)(CURL*)> curl(curl_easy_init(), curl_easy_cleanup);
  char* e = curl_easy_escape(curl.get(), text.c_str(), static_cast<int>(text.size()));
  std::string out = e ? e : "";
  curl_free(e);
  return out;
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
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<Match> webFind(const Server& server, const std::string& level, const Match& keys,
                           const Options& options) {
  warnInsecure(server, options);
  auto key = [&](const char* k) {
    auto it = keys.find(k);
    return it == keys.end() ? std::string() : it->second;
  };
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
    query += v.empty() ? "includefield=" + k : k + "=" + escape(v);
  }
  Response r = request(server, url + query, "application/dicom+json", kMaxQueryBytes, options);
  std::vector<Match> matches;
  if (r.status == 204 || r.body.empty()) return matches;
  json answer = json::parse(r.body, nullptr, false);
  if (answer.is_discarded() || !answer.is_array())
    throw ServiceError(server.text +
                       ": answered the QIDO-RS request with something that is not "
                       "a DICOM JSON array: '" +
                       printable(r.body, 60) + "'");
  if (answer.size() > kMaxMatches)
    throw ServiceError(server.text + ": answered more than " + std::to_string(kMaxMatches) +
                       " matches");
  for (const json& object : answer) {
    if (!object.is_object())
      throw ServiceError(server.text + ": answered a match that is not a DICOM JSON object");
    Match m;
    for (const auto& [tag, element] : object.items()) {
      if (tag.size() != 8 || tag.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
        throw ServiceError(server.text + ": answered a DICOM JSON key that is not a tag: '" +
                           printable(tag, 20) + "'");
      const unsigned long t = std::stoul(tag, nullptr, 16);
      const std::string keyword = keywordOf(t >> 16, t & 0xffff);
      if (!keyword.empty()) m[keyword] = valueText(element);
    }
    // The path's UIDs belong to the match as well (Orthanc repeats them; others may not).
    for (const std::string& k : inPath)
      if (!m.count(k)) m[k] = key(k.c_str());
    matches.push_back(std::move(m));
  }
  return matches;
}

namespace {

// The boundary parameter of a multipart/related Content-Type.
std::string boundaryOf(const Server& server, const std::string& contentType) {
  std::string lowerType = contentType;
  std::transform(lowerType.begin(), lowerType.end(), lowerType.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (lowerType.rfind("multipart/related", 0) != 0)
    throw ServiceError(server.text + ": answered the WADO-RS request with '" +
                       printable(contentType, 80) + "', not multipart/related");
  const auto at = lowerType.find("boundary=");
  if (at == std::string::npos)
    throw ServiceError(server.text + ": answered multipart/related without a boundary");
  std::string b = contentType.substr(at + 9);
  if (!b.empty() && b.front() == '"') {
    const auto end = b.find('"', 1);
    if (end == std::string::npos)
      throw ServiceError(server.text + ": answered a multipart boundary without its closing quote");
    b = b.substr(1, end - 1);
  } else {
    b = b.substr(0, b.find_first_of("; \t"));
  }
  if (b.empty() || b.size() > 70)
    throw ServiceError(server.text + ": answered a multipart boundary of " +
                       std::to_string(b.size()) + " characters (1 .. 70 allowed)");
  return b;
}

// Each part of a multipart/related body (RFC 2046), written whole to the staging folder and
// handed to the receiver. Bounded: parts, header sizes; a body that ends without its closing
// delimiter broke off.
void parseMultipart(const Server& server, const std::string& contentType, std::string_view body,
                    Receiver& receiver) {
  const std::string delimiter = "--" + boundaryOf(server, contentType);
  auto brokeOff = [&](const std::string& why) {
    throw ServiceError(server.text + ": the WADO-RS answer " + why);
  };
  std::size_t pos = body.find(delimiter);
  if (pos == std::string_view::npos) brokeOff("holds no multipart delimiter");
  pos += delimiter.size();
  std::size_t parts = 0;
  const std::string next = "\r\n" + delimiter;
  for (;;) {
    if (body.substr(pos, 2) == "--") return;  // the closing delimiter
    // Transport padding, then CRLF.
    while (pos < body.size() && (body[pos] == ' ' || body[pos] == '\t')) ++pos;
    if (body.substr(pos, 2) != "\r\n") brokeOff("broke off after a delimiter");
    pos += 2;
    const std::size_t headersEnd = body.find("\r\n\r\n", pos);
    std::size_t contentStart;
    if (body.substr(pos, 2) == "\r\n") {
      contentStart = pos + 2;  // a part without headers
    } else {
      if (headersEnd == std::string_view::npos || headersEnd - pos > kMaxPartHeaderBytes)
        brokeOff("has a part whose headers do not end within " +
                 std::to_string(kMaxPartHeaderBytes) + " bytes");
      std::string headers(body.substr(pos, headersEnd - pos));
      std::transform(headers.begin(), headers.end(), headers.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
      const auto typeAt = headers.find("content-type:");
      if (typeAt != std::string::npos) {
        const std::string type =
            headers.substr(typeAt + 13, headers.find("\r\n", typeAt) - typeAt - 13);
        if (type.find("application/dicom") == std::string::npos)
          brokeOff("has a part of type '" + printable(type, 60) + "', not application/dicom");
      }
      contentStart = headersEnd + 4;
    }
    const std::size_t contentEnd = body.find(next, contentStart);
    if (contentEnd == std::string_view::npos) brokeOff("broke off inside a part");
    if (++parts > kMaxParts) brokeOff("has more than " + std::to_string(kMaxParts) + " parts");
    const fs::path tmp = receiver.staging() / (".part-" + std::to_string(parts));
    {
      std::FILE* f = std::fopen(tmp.c_str(), "wb");
      if (!f) throw Error("cannot write " + tmp.string());
      const std::size_t n = contentEnd - contentStart;
      const bool ok = std::fwrite(body.data() + contentStart, 1, n, f) == n;
      if (std::fclose(f) != 0 || !ok) throw Error("cannot write " + tmp.string());
    }
    receiver.acceptFile(tmp);
    pos = contentEnd + next.size();
  }
}

}  // namespace

void webRetrieve(const Server& server, const std::string& studyUid, const std::string& seriesUid,
                 const std::vector<std::string>& instances, Receiver& receiver,
                 const Options& options) {
  warnInsecure(server, options);
  const std::string accept = "multipart/related; type=\"application/dicom\"; transfer-syntax=*";
  const std::string series = server.baseUrl + "/studies/" + studyUid + "/series/" + seriesUid;
  std::vector<std::string> urls;
  if (instances.empty())
    urls.push_back(series);
  else
    for (const std::string& uid : instances) urls.push_back(series + "/instances/" + uid);
  for (const std::string& url : urls) {
    Response r = request(server, url, accept, kMaxRetrieveBytes, options);
    parseMultipart(server, r.contentType, r.body, receiver);
  }
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

}  // namespace mvw::pacs::detail
