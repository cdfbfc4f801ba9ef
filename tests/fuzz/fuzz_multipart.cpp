// libFuzzer: the WADO-RS multipart/related parser (pacs' internal MultipartParser), fed as the
// network feeds it. The input is one byte that picks the slicing and the limits, the answer's
// Content-Type up to the first '\n', then the body. The body goes in slices whose sizes a
// generator seeded by the first byte draws (1 byte, up to 7, 64 or 4096, or all at once), and
// again in one piece: both must end alike, with the same parts, byte for byte, whatever the
// slicing. MultipartError (what DicomWeb.cpp turns into a ServiceError) is a refusal; a crash,
// any other exception or a difference between the two runs is a finding.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "FuzzInput.h"
#include "Multipart.h"

namespace {

using mvw::pacs::detail::MultipartError;
using mvw::pacs::detail::MultipartLimits;
using mvw::pacs::detail::MultipartParser;

// The parts as the sink saw them; begin/data/end out of order is a finding.
class Parts : public mvw::pacs::detail::MultipartSink {
 public:
  void begin(std::size_t index) override {
    if (open_ || index != parts.size() + 1) mvw::fuzz::finding("multipart: begin out of order");
    parts.emplace_back();
    open_ = true;
  }
  void data(const char* bytes, std::size_t n) override {
    if (!open_) mvw::fuzz::finding("multipart: data outside a part");
    parts.back().append(bytes, n);
  }
  void end() override {
    if (!open_) mvw::fuzz::finding("multipart: end without a begin");
    open_ = false;
  }
  std::vector<std::string> parts;

 private:
  bool open_ = false;
};

struct Outcome {
  bool refused = false;
  bool done = false;
  std::vector<std::string> parts;
};

// Small limits half the time, so that every bound is reached by small inputs.
MultipartLimits limitsFor(std::uint8_t control) {
  if (!(control & 0x80)) return {};
  MultipartLimits small;
  small.maxPreambleBytes = 64;
  small.maxPartHeaderBytes = 96;
  small.maxPartBytes = 512;
  small.maxTotalBytes = 2048;
  small.maxParts = 4;
  return small;
}

Outcome parse(const std::string& contentType, std::string_view body, std::uint8_t control,
              bool sliced) {
  Outcome out;
  Parts sink;
  try {
    MultipartParser parser(mvw::pacs::detail::multipartBoundary(contentType), sink,
                           limitsFor(control));
    std::uint32_t state = 2463534242u ^ control;  // xorshift32
    const std::size_t maxSlice[] = {1, 7, 64, 4096, body.size() + 1};
    const std::size_t most = maxSlice[(control & 0x7f) % 5];
    std::size_t at = 0;
    while (at < body.size()) {
      state ^= state << 13;
      state ^= state >> 17;
      state ^= state << 5;
      const std::size_t n = sliced ? std::min(body.size() - at, 1 + state % most) : body.size();
      parser.feed(body.substr(at, n));
      at += n;
    }
    parser.finish();
    out.done = parser.done();
    if (parser.parts() != sink.parts.size()) mvw::fuzz::finding("multipart: parts miscounted");
  } catch (const MultipartError& e) {
    out.refused = true;
    if (const char* v = std::getenv("MVW_FUZZ_VERBOSE"); v && *v == '1' && sliced)
      std::fprintf(stderr, "refused: %s\n", e.what());
  }
  out.parts = std::move(sink.parts);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t control = data[0];
  const std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  const auto eol = rest.find('\n');
  const std::string contentType(rest.substr(0, eol));
  const std::string_view body = eol == std::string_view::npos ? "" : rest.substr(eol + 1);
  mvw::fuzz::expectOnly<>([&] {
    const Outcome sliced = parse(contentType, body, control, true);
    const Outcome whole = parse(contentType, body, control, false);
    if (sliced.refused != whole.refused || sliced.done != whole.done)
      mvw::fuzz::finding("multipart: sliced and whole input end differently");
    // Parts delivered before a refusal may differ in where they stop; a complete answer may not.
    if (!whole.refused && sliced.parts != whole.parts)
      mvw::fuzz::finding("multipart: sliced and whole input give different parts");
  });
  return 0;
}
