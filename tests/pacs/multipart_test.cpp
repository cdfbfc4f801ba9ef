// The WADO-RS multipart/related parser (modules/pacs/src/Multipart.h), which parses an answer
// while it downloads: the same parts whatever slices the bytes arrive in (every split point,
// byte by byte), a boundary-like text inside a part's data, a truncated answer at every length,
// and each bound (part size, headers, parts, preamble, the whole answer).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "Multipart.h"

namespace mvw::pacs::detail {
namespace {

struct Collect : MultipartSink {
  std::vector<std::string> parts;
  bool open = false;
  void begin(std::size_t index) override {
    EXPECT_FALSE(open);
    EXPECT_EQ(index, parts.size() + 1);
    parts.emplace_back();
    open = true;
  }
  void data(const char* bytes, std::size_t n) override {
    ASSERT_TRUE(open);
    parts.back().append(bytes, n);
  }
  void end() override {
    EXPECT_TRUE(open);
    open = false;
  }
};

const std::string kBoundary = "b0und-ary";

// Part contents that tempt a parser: the boundary without its CRLF, a CRLF and a partial
// delimiter, CRLFs, NUL bytes, a part that is empty.
std::vector<std::string> trickyParts() {
  std::string binary;
  for (int i = 0; i < 300; ++i) binary += static_cast<char>((i * 37) & 0xff);
  return {"DICM" + binary, "--" + kBoundary + " not at a line start\r\n--b0und-ar\r\n--b0und", "",
          std::string("\0\r\n\r\n\0", 6) + "\r\n-" + binary + "\r\n--"};
}

std::string body(const std::vector<std::string>& parts, bool headers = true) {
  std::string b = "preamble text\r\n";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    b += "--" + kBoundary + (i == 1 ? " \t" : "") + "\r\n";  // padding after one delimiter
    if (headers) b += "Content-Type: application/dicom\r\nContent-Length: ignored\r\n";
    b += "\r\n" + parts[i] + "\r\n";
  }
  return b + "--" + kBoundary + "--\r\nepilogue";
}

std::vector<std::string> parse(const std::string& text, const std::vector<std::size_t>& cuts,
                               MultipartLimits limits = {}) {
  Collect sink;
  MultipartParser parser(kBoundary, sink, limits);
  std::size_t from = 0;
  for (std::size_t cut : cuts) {
    parser.feed(std::string_view(text).substr(from, cut - from));
    from = cut;
  }
  parser.feed(std::string_view(text).substr(from));
  parser.finish();
  EXPECT_FALSE(sink.open);
  return sink.parts;
}

TEST(PacsMultipart, TheSamePartsWhereverTheBytesAreSplit) {
  const std::vector<std::string> parts = trickyParts();
  for (bool headers : {true, false}) {
    const std::string text = body(parts, headers);
    ASSERT_EQ(parse(text, {}), parts);
    for (std::size_t cut = 0; cut <= text.size(); ++cut)
      ASSERT_EQ(parse(text, {cut}), parts) << cut;
    for (std::size_t cut = 0; cut + 7 <= text.size(); ++cut)
      ASSERT_EQ(parse(text, {cut, cut + 7}), parts) << cut;
    std::vector<std::size_t> everyByte;
    for (std::size_t i = 1; i < text.size(); ++i) everyByte.push_back(i);
    ASSERT_EQ(parse(text, everyByte), parts);
  }
}

TEST(PacsMultipart, ATruncatedAnswerBrokeOffAtEveryLength) {
  const std::string text = body(trickyParts());
  const std::size_t closing = text.find("--" + kBoundary + "--");
  for (std::size_t n = 0; n < closing + kBoundary.size() + 4; ++n) {
    Collect sink;
    MultipartParser parser(kBoundary, sink);
    parser.feed(std::string_view(text).substr(0, n));
    try {
      parser.finish();
      FAIL() << "a body cut at " << n << " of " << text.size() << " bytes was accepted";
    } catch (const MultipartError& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.find("broke off") != std::string::npos ||
                  what.find("holds no multipart delimiter") != std::string::npos)
          << what;
    }
  }
}

TEST(PacsMultipart, ABodyWithoutItsClosingDelimiterBrokeOff) {
  Collect sink;
  MultipartParser parser("b", sink);
  parser.feed("--b\r\nContent-Type: application/dicom\r\n\r\nDICM?");
  EXPECT_THROW(
      {
        try {
          parser.finish();
        } catch (const MultipartError& e) {
          EXPECT_STREQ(e.what(), "the WADO-RS answer broke off inside a part");
          throw;
        }
      },
      MultipartError);
}

void expectRefused(const std::string& text, MultipartLimits limits, const std::string& why) {
  for (std::size_t cut : {std::size_t{0}, text.size() / 2}) {
    Collect sink;
    MultipartParser parser(kBoundary, sink, limits);
    try {
      parser.feed(std::string_view(text).substr(0, cut));
      parser.feed(std::string_view(text).substr(cut));
      parser.finish();
      ADD_FAILURE() << "accepted; expected: " << why;
    } catch (const MultipartError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

TEST(PacsMultipart, EveryBoundHolds) {
  MultipartLimits small;
  small.maxPartBytes = 100;
  EXPECT_EQ(parse(body({std::string(100, 'x')}), {}, small).front().size(), 100u);
  expectRefused(body({std::string(101, 'x')}), small, "has a part larger than 100 bytes");

  MultipartLimits headers;
  headers.maxPartHeaderBytes = 64;
  expectRefused("--" + kBoundary + "\r\nX-Long: " + std::string(80, 'h') + "\r\n\r\ndata\r\n--" +
                    kBoundary + "--",
                headers, "headers do not end within 64 bytes");
  // Headers that never end: refused once past the bound, not buffered without end.
  Collect sink;
  MultipartParser endless(kBoundary, sink, headers);
  endless.feed("--" + kBoundary + "\r\n");
  EXPECT_THROW(endless.feed(std::string(200, 'h')), MultipartError);

  MultipartLimits two;
  two.maxParts = 2;
  EXPECT_EQ(parse(body({"a", "b"}), {}, two).size(), 2u);
  expectRefused(body({"a", "b", "c"}), two, "has more than 2 parts");

  MultipartLimits preamble;
  preamble.maxPreambleBytes = 32;
  expectRefused(std::string(100, 'p') + body({"a"}), preamble, "holds no multipart delimiter");

  MultipartLimits total;
  total.maxTotalBytes = 200;
  expectRefused(body({std::string(300, 'x')}), total, "exceeds 200 bytes");

  expectRefused(
      "--" + kBoundary + "\r\nContent-Type: text/html\r\n\r\n<html>\r\n--" + kBoundary + "--", {},
      "has a part of type ' text/html', not application/dicom");
  expectRefused("--" + kBoundary + "garbage\r\n\r\nx\r\n--" + kBoundary + "--", {},
                "broke off after a delimiter");
}

TEST(PacsMultipart, TheBoundaryComesFromTheContentType) {
  EXPECT_EQ(multipartBoundary("multipart/related; type=\"application/dicom\"; boundary=abc"),
            "abc");
  EXPECT_EQ(multipartBoundary("Multipart/Related; boundary=\"a b;c\"; type=x"), "a b;c");
  EXPECT_EQ(multipartBoundary("multipart/related;boundary=xyz;type=\"application/dicom\""), "xyz");
  EXPECT_THROW(multipartBoundary("application/dicom"), MultipartError);
  EXPECT_THROW(multipartBoundary("multipart/related; type=x"), MultipartError);
  EXPECT_THROW(multipartBoundary("multipart/related; boundary=\"abc"), MultipartError);
  EXPECT_THROW(multipartBoundary("multipart/related; boundary=" + std::string(71, 'b')),
               MultipartError);
  EXPECT_THROW(multipartBoundary("multipart/related; boundary="), MultipartError);
}

}  // namespace
}  // namespace mvw::pacs::detail
