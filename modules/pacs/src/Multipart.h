#pragma once
// A multipart/related body (RFC 2046), as WADO-RS answers a retrieve, parsed while it arrives:
// feed() takes the bytes in whatever slices the network delivers them, and each part's content
// goes to a sink as it comes (begin, data..., end), so memory stays bounded by one slice plus a
// delimiter, never the whole answer. Strictly bounded: the preamble, each part's headers, each
// part's size, the count of parts and the whole answer.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mvw::pacs::detail {

// What is wrong with the answer, in words that follow "the WADO-RS answer ...".
class MultipartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct MultipartLimits {
  std::size_t maxPreambleBytes = 64u << 10;
  std::size_t maxPartHeaderBytes = 16u << 10;
  std::uint64_t maxPartBytes = std::uint64_t{4} << 30;
  std::uint64_t maxTotalBytes = std::uint64_t{4} << 30;
  std::size_t maxParts = 100000;
};

class MultipartSink {
 public:
  virtual ~MultipartSink() = default;
  // A part starts (its headers checked: none, or a Content-Type of application/dicom).
  virtual void begin(std::size_t index) = 0;
  virtual void data(const char* bytes, std::size_t n) = 0;
  // The part ended at its delimiter.
  virtual void end() = 0;
};

// The boundary parameter of a multipart/related Content-Type; MultipartError for another type
// or a boundary that is missing, unquoted badly, or not 1 .. 70 characters.
std::string multipartBoundary(const std::string& contentType);

// At most `max` bytes of what a server sent, each byte outside printable ASCII as a space: the
// quote of a server's answer in a message (stricter than core's printable, which keeps UTF-8:
// a server's bytes are not a name the user typed).
std::string printable(std::string_view text, std::size_t max);

class MultipartParser {
 public:
  MultipartParser(const std::string& boundary, MultipartSink& sink, MultipartLimits limits = {});
  // The next bytes of the body. MultipartError when they break the format or a bound; what the
  // sink throws passes through.
  void feed(const char* bytes, std::size_t n);
  void feed(std::string_view bytes) { feed(bytes.data(), bytes.size()); }
  // The body ended: MultipartError unless the closing delimiter was seen.
  void finish();
  std::size_t parts() const { return parts_; }
  bool done() const { return state_ == State::Done; }

 private:
  enum class State { Preamble, AfterDelimiter, Headers, Content, Done };
  // One step at buf_[pos_]; false when it needs more bytes.
  bool step();
  void beginPart();

  std::string delimiter_;  // "--" boundary
  std::string next_;       // CRLF "--" boundary: the end of a part's content
  MultipartSink& sink_;
  MultipartLimits limits_;
  State state_ = State::Preamble;
  std::string buf_;  // bytes not yet consumed: at most a slice plus a delimiter or headers
  std::size_t pos_ = 0;
  std::uint64_t total_ = 0;
  std::uint64_t preamble_ = 0;
  std::uint64_t partBytes_ = 0;
  std::size_t padding_ = 0;
  std::size_t parts_ = 0;
};

}  // namespace mvw::pacs::detail
