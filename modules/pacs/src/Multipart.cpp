#include "Multipart.h"

#include <algorithm>
#include <cctype>

namespace mvw::pacs::detail {

std::string printable(std::string_view text, std::size_t max) {
  std::string out;
  for (char c : text.substr(0, max)) out += (c >= 32 && c < 127) ? c : ' ';
  return out;
}

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return out;
}

std::string sizeText(std::uint64_t bytes) {
  return bytes >= (1u << 20) ? std::to_string(bytes >> 20) + " MB"
                             : std::to_string(bytes) + " bytes";
}

[[noreturn]] void fail(const std::string& why) {
  throw MultipartError("the WADO-RS answer " + why);
}

}  // namespace

std::string multipartBoundary(const std::string& contentType) {
  const std::string lowerType = lower(contentType);
  if (lowerType.rfind("multipart/related", 0) != 0)
    throw MultipartError("answered the WADO-RS request with '" + printable(contentType, 80) +
                         "', not multipart/related");
  const auto at = lowerType.find("boundary=");
  if (at == std::string::npos)
    throw MultipartError("answered multipart/related without a boundary");
  std::string b = contentType.substr(at + 9);
  if (!b.empty() && b.front() == '"') {
    const auto end = b.find('"', 1);
    if (end == std::string::npos)
      throw MultipartError("answered a multipart boundary without its closing quote");
    b = b.substr(1, end - 1);
  } else {
    b = b.substr(0, b.find_first_of("; \t"));
  }
  if (b.empty() || b.size() > 70)
    throw MultipartError("answered a multipart boundary of " + std::to_string(b.size()) +
                         " characters (1 .. 70 allowed)");
  return b;
}

MultipartParser::MultipartParser(const std::string& boundary, MultipartSink& sink,
                                 MultipartLimits limits)
    : delimiter_("--" + boundary), next_("\r\n--" + boundary), sink_(sink), limits_(limits) {}

void MultipartParser::feed(const char* bytes, std::size_t n) {
  total_ += n;
  if (total_ > limits_.maxTotalBytes) fail("exceeds " + sizeText(limits_.maxTotalBytes));
  if (state_ == State::Done) return;  // the epilogue: ignored
  buf_.append(bytes, n);
  while (state_ != State::Done && step()) {
  }
  // Only what is still undecided stays: a possible delimiter's start, or headers.
  buf_.erase(0, pos_);
  pos_ = 0;
}

void MultipartParser::beginPart() {
  if (++parts_ > limits_.maxParts)
    fail("has more than " + std::to_string(limits_.maxParts) + " parts");
  partBytes_ = 0;
  sink_.begin(parts_);
}

bool MultipartParser::step() {
  const std::string_view view = std::string_view(buf_).substr(pos_);
  switch (state_) {
    case State::Preamble: {
      const auto at = view.find(delimiter_);
      if (at == std::string_view::npos) {
        // Keep what may be the delimiter's start; the rest is preamble.
        const std::size_t keep = std::min(view.size(), delimiter_.size() - 1);
        preamble_ += view.size() - keep;
        pos_ += view.size() - keep;
        if (preamble_ > limits_.maxPreambleBytes)
          fail("holds no multipart delimiter within its first " +
               std::to_string(limits_.maxPreambleBytes) + " bytes");
        return false;
      }
      preamble_ += at;
      if (preamble_ > limits_.maxPreambleBytes)
        fail("holds no multipart delimiter within its first " +
             std::to_string(limits_.maxPreambleBytes) + " bytes");
      pos_ += at + delimiter_.size();
      state_ = State::AfterDelimiter;
      padding_ = 0;
      return true;
    }
    case State::AfterDelimiter: {
      // "--": the closing delimiter; else transport padding, then CRLF.
      std::size_t i = 0;
      if (padding_ == 0) {
        if (view.size() < 2) return false;
        if (view.substr(0, 2) == "--") {
          pos_ += 2;
          state_ = State::Done;
          return false;
        }
      }
      while (i < view.size() && (view[i] == ' ' || view[i] == '\t')) ++i;
      padding_ += i;
      pos_ += i;
      if (padding_ > limits_.maxPartHeaderBytes) fail("broke off after a delimiter");
      if (view.size() - i < 2) return false;
      if (view.substr(i, 2) != "\r\n") fail("broke off after a delimiter");
      pos_ += 2;
      state_ = State::Headers;
      return true;
    }
    case State::Headers: {
      if (view.size() < 2) return false;
      if (view.substr(0, 2) == "\r\n") {  // a part without headers
        pos_ += 2;
        beginPart();
        state_ = State::Content;
        return true;
      }
      const auto end = view.find("\r\n\r\n");
      if (end == std::string_view::npos || end > limits_.maxPartHeaderBytes) {
        if (end != std::string_view::npos || view.size() > limits_.maxPartHeaderBytes + 3)
          fail("has a part whose headers do not end within " +
               std::to_string(limits_.maxPartHeaderBytes) + " bytes");
        return false;
      }
      const std::string headers = lower(view.substr(0, end));
      const auto typeAt = headers.find("content-type:");
      if (typeAt != std::string::npos) {
        const std::string type =
            headers.substr(typeAt + 13, headers.find("\r\n", typeAt) - typeAt - 13);
        if (type.find("application/dicom") == std::string::npos)
          fail("has a part of type '" + printable(type, 60) + "', not application/dicom");
      }
      pos_ += end + 4;
      beginPart();
      state_ = State::Content;
      return true;
    }
    case State::Content: {
      const auto at = view.find(next_);
      // Up to the delimiter, or all but what may be its start.
      const std::size_t n =
          at != std::string_view::npos ? at : view.size() - std::min(view.size(), next_.size() - 1);
      partBytes_ += n;
      if (partBytes_ > limits_.maxPartBytes)
        fail("has a part larger than " + sizeText(limits_.maxPartBytes));
      if (n) sink_.data(view.data(), n);
      pos_ += n;
      if (at == std::string_view::npos) return false;
      pos_ += next_.size();
      sink_.end();
      state_ = State::AfterDelimiter;
      padding_ = 0;
      return true;
    }
    case State::Done:
      return false;
  }
  return false;
}

void MultipartParser::finish() {
  switch (state_) {
    case State::Done:
      return;
    case State::Preamble:
      fail("holds no multipart delimiter");
    case State::AfterDelimiter:
      fail("broke off after a delimiter");
    case State::Headers:
      fail("broke off inside a part's headers");
    case State::Content:
      fail("broke off inside a part");
  }
}

}  // namespace mvw::pacs::detail
