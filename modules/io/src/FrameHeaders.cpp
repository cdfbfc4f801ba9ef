#include "FrameHeaders.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <utility>
#include <vector>

#include <vtkDICOMMetaData.h>
#include <vtkDICOMParser.h>
#include <vtkNew.h>

#include "mvw/core/Error.h"

namespace mvw::io::detail {

namespace {

using Bytes = std::span<const std::uint8_t>;
using Result = FrameCheck::Result;

unsigned be16(Bytes b, std::size_t at) { return (b[at] << 8u) | b[at + 1]; }

std::uint32_t be32(Bytes b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24u) | (std::uint32_t{b[at + 1]} << 16u) |
         (std::uint32_t{b[at + 2]} << 8u) | b[at + 3];
}

std::uint32_t le32(Bytes b, std::size_t at) {
  return (std::uint32_t{b[at + 3]} << 24u) | (std::uint32_t{b[at + 2]} << 16u) |
         (std::uint32_t{b[at + 1]} << 8u) | b[at];
}

FrameCheck mismatch(std::string problem) { return {Result::Mismatch, std::move(problem)}; }

// The header ended inside `head`: more to read, or a frame cut short.
FrameCheck endedEarly(Bytes head, std::uint64_t frameBytes, const std::string& what) {
  if (head.size() < frameBytes) return {Result::NeedMore, ""};
  return mismatch("the frame ends before its " + what + " header does");
}

std::string sizeText(long long columns, long long rows) {
  return std::to_string(columns) + " x " + std::to_string(rows);
}

// The parts of a frame header the decoder sizes its writes from, against the DICOM header.
FrameCheck compare(const std::string& codec, const FrameLayout& layout, long long columns,
                   long long rows, long long components, long long precision) {
  if (columns != layout.columns || rows != layout.rows)
    return mismatch("its " + codec + " header says " + sizeText(columns, rows) +
                    " pixels (columns x rows), the DICOM header " +
                    sizeText(layout.columns, layout.rows));
  if (components != layout.samples)
    return mismatch("its " + codec + " header says " + std::to_string(components) +
                    " components, the DICOM header (SamplesPerPixel) " +
                    std::to_string(layout.samples));
  // Fewer bits than BitsStored is common and harmless (GDCM widens them); more than
  // BitsAllocated would be written past each sample's bytes.
  if (precision > layout.bitsAllocated)
    return mismatch("its " + codec + " header says " + std::to_string(precision) +
                    "-bit samples, the DICOM header (BitsAllocated) " +
                    std::to_string(layout.bitsAllocated));
  return {};
}

bool isStartOfFrame(unsigned marker) {
  // SOF0-3, 5-7, 9-11, 13-15 (0xC4 DHT, 0xC8 JPG and 0xCC DAC are not) and JPEG-LS SOF55.
  return (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) ||
         marker == 0xF7;
}

// JPEG and JPEG-LS share the marker syntax: walk the segments to the frame header.
FrameCheck checkJpeg(const FrameLayout& layout, Bytes head, std::uint64_t frameBytes,
                     const std::string& codec) {
  if (head.size() < 2) return endedEarly(head, frameBytes, codec);
  if (head[0] != 0xFF || head[1] != 0xD8)
    return mismatch("it does not begin with a JPEG start-of-image marker");
  std::size_t at = 2;
  for (;;) {
    // Bytes between segments are skipped, as libjpeg does (with a warning).
    while (at < head.size() && head[at] != 0xFF) ++at;
    while (at + 1 < head.size() && head[at + 1] == 0xFF) ++at;  // fill bytes
    if (at + 2 > head.size()) return endedEarly(head, frameBytes, codec);
    const unsigned marker = head[at + 1];
    if (marker == 0x01 || marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7)) {
      at += 2;  // no length
      continue;
    }
    if (marker == 0xDA || marker == 0xD9)
      return mismatch("its " + codec + " data has no frame header (SOF) before its scan");
    if (at + 4 > head.size()) return endedEarly(head, frameBytes, codec);
    const unsigned length = be16(head, at + 2);
    if (length < 2)
      return mismatch("its " + codec + " header holds a segment of length " +
                      std::to_string(length));
    if (isStartOfFrame(marker)) {
      // Lf, P, Y, X, Nf
      if (length < 8) return mismatch("its " + codec + " frame header (SOF) is too short");
      if (at + 10 > head.size()) return endedEarly(head, frameBytes, codec);
      return compare(codec, layout, be16(head, at + 7), be16(head, at + 5), head[at + 9],
                     head[at + 4]);
    }
    at += 2 + length;
  }
}

constexpr std::array<std::uint8_t, 4> kCodestream{0xFF, 0x4F, 0xFF, 0x51};  // SOC, SIZ
constexpr std::array<std::uint8_t, 8> kJp2Signature{0x00, 0x00, 0x00, 0x0C, 0x6A, 0x50, 0x20, 0x20};

bool startsWith(Bytes b, std::span<const std::uint8_t> prefix) {
  return b.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), b.begin());
}

FrameCheck checkJpeg2000(const FrameLayout& layout, Bytes head, std::uint64_t frameBytes) {
  const std::string codec = "JPEG 2000";
  std::size_t at = 0;
  if (startsWith(head, kJp2Signature)) {
    // A JP2 file (not allowed in DICOM, read by GDCM all the same): its codestream.
    const auto found =
        std::search(head.begin(), head.end(), kCodestream.begin(), kCodestream.end());
    if (found == head.end()) return endedEarly(head, frameBytes, codec);
    at = static_cast<std::size_t>(found - head.begin());
  } else if (head.size() < 4) {
    return endedEarly(head, frameBytes, codec);
  } else if (!startsWith(head, kCodestream)) {
    return mismatch("it does not begin with a JPEG 2000 codestream (SOC and SIZ markers)");
  }
  // From SIZ: Lsiz Rsiz Xsiz Ysiz XOsiz YOsiz XTsiz YTsiz XTOsiz YTOsiz Csiz, then Ssiz XRsiz
  // YRsiz per component.
  const std::size_t siz = at + 2;
  if (siz + 40 > head.size()) return endedEarly(head, frameBytes, codec);
  const long long xsiz = be32(head, siz + 6), ysiz = be32(head, siz + 10);
  const long long xosiz = be32(head, siz + 14), yosiz = be32(head, siz + 18);
  const long long components = be16(head, siz + 38);
  if (siz + 40 + 3 * static_cast<std::size_t>(components) > head.size())
    return endedEarly(head, frameBytes, codec);
  long long precision = 0;
  for (long long c = 0; c < components; ++c)
    precision = std::max<long long>(precision,
                                    (head[siz + 40 + 3 * static_cast<std::size_t>(c)] & 0x7F) + 1);
  return compare(codec, layout, xsiz - xosiz, ysiz - yosiz, components, precision);
}

FrameCheck checkRle(const FrameLayout& layout, Bytes head, std::uint64_t frameBytes) {
  if (head.size() < 64) return endedEarly(head, frameBytes, "RLE");
  const long long segments = le32(head, 0);
  const long long expected = layout.samples * ((layout.bitsAllocated + 7) / 8);
  if (segments != expected)
    return mismatch("its RLE header lists " + std::to_string(segments) +
                    " segments, the DICOM header (SamplesPerPixel x BitsAllocated / 8) " +
                    std::to_string(expected));
  std::uint64_t previous = 64;
  for (long long s = 0; s < segments; ++s) {
    const std::uint64_t offset = le32(head, 4 + 4 * static_cast<std::size_t>(s));
    if (offset < previous || offset >= frameBytes)
      return mismatch("its RLE header puts segment " + std::to_string(s + 1) + " at byte " +
                      std::to_string(offset) + ", outside the " + std::to_string(frameBytes) +
                      "-byte frame or before the segment ahead of it");
    previous = offset;
  }
  return {};
}

}  // namespace

FrameCodec frameCodecOf(const std::string& ts) {
  const std::string jpegFamily = "1.2.840.10008.1.2.4.";
  if (ts == "1.2.840.10008.1.2.5") return FrameCodec::Rle;
  if (ts.rfind(jpegFamily, 0) != 0) return FrameCodec::None;
  const std::string last = ts.substr(jpegFamily.size());
  if (last.empty() || !std::all_of(last.begin(), last.end(), ::isdigit) || last.size() > 3)
    return FrameCodec::None;
  const int n = std::stoi(last);
  if ((n >= 50 && n <= 66) || n == 70) return FrameCodec::Jpeg;  // retired ones too
  if (n == 80 || n == 81) return FrameCodec::JpegLs;
  if ((n >= 90 && n <= 93) || (n >= 201 && n <= 203)) return FrameCodec::Jpeg2000;  // and HTJ2K
  return FrameCodec::None;
}

FrameCheck checkFrameHeader(FrameCodec codec, const FrameLayout& layout, Bytes head,
                            std::uint64_t frameBytes) {
  switch (codec) {
    case FrameCodec::Jpeg:
      return checkJpeg(layout, head, frameBytes, "JPEG");
    case FrameCodec::JpegLs:
      return checkJpeg(layout, head, frameBytes, "JPEG-LS");
    case FrameCodec::Jpeg2000:
      return checkJpeg2000(layout, head, frameBytes);
    case FrameCodec::Rle:
      return checkRle(layout, head, frameBytes);
    case FrameCodec::None:
      break;
  }
  return {};
}

bool startsFrame(FrameCodec codec, Bytes head) {
  switch (codec) {
    case FrameCodec::Jpeg:
    case FrameCodec::JpegLs:
      return head.size() >= 2 && head[0] == 0xFF && head[1] == 0xD8;
    case FrameCodec::Jpeg2000:
      return startsWith(head, kCodestream) || startsWith(head, kJp2Signature);
    case FrameCodec::Rle:
      return true;  // one fragment per frame (PS3.5 G.2)
    case FrameCodec::None:
      break;
  }
  return false;
}

namespace {

struct Fragment {
  std::uint64_t offset = 0, length = 0;  // of its bytes in the file
};

// The fragments after the basic offset table, as far as they can be followed. Anything else
// (a tag that is no item, a length past the end) ends the list: what follows is the decoder's
// to refuse.
std::vector<Fragment> fragmentsOf(std::ifstream& in, std::uint64_t valueOffset,
                                  std::uint64_t fileSize) {
  std::vector<Fragment> fragments;
  std::uint64_t at = valueOffset;
  bool offsetTable = true;
  while (at + 8 <= fileSize) {
    std::array<std::uint8_t, 8> item{};
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(item.data()), item.size())) break;
    const Bytes b(item);
    if (le32(b, 0) != 0xE000FFFEu) break;  // (FFFE,E000) Item; the delimiter ends the list
    const std::uint64_t length = le32(b, 4);
    at += 8;
    if (length > fileSize - at) break;
    if (!offsetTable) fragments.push_back({at, length});
    offsetTable = false;
    at += length;
  }
  return fragments;
}

std::vector<std::uint8_t> readSpan(std::ifstream& in, const std::vector<Fragment>& fragments,
                                   std::size_t first, std::size_t end, std::size_t want) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t f = first; f < end && bytes.size() < want; ++f) {
    const std::size_t n =
        static_cast<std::size_t>(std::min<std::uint64_t>(fragments[f].length, want - bytes.size()));
    const std::size_t old = bytes.size();
    bytes.resize(old + n);
    in.seekg(static_cast<std::streamoff>(fragments[f].offset));
    if (!in.read(reinterpret_cast<char*>(bytes.data() + old), static_cast<std::streamsize>(n))) {
      bytes.resize(old);
      break;
    }
  }
  return bytes;
}

}  // namespace

void checkEncapsulatedFrames(const std::filesystem::path& file, FrameCodec codec,
                             const FrameLayout& layout, long long frames) {
  if (codec == FrameCodec::None) return;
  vtkNew<vtkDICOMMetaData> meta;
  vtkNew<vtkDICOMParser> parser;
  parser->SetMetaData(meta);
  parser->SetFileName(file.c_str());
  parser->Update();
  // A file vtk-dicom cannot parse, or one without encapsulated pixel data, is the reader's to
  // refuse (it already read this header once).
  if (parser->GetErrorCode() != 0 || !parser->GetPixelDataFound() ||
      parser->GetPixelDataVL() != 0xFFFFFFFFu)
    return;
  std::ifstream in(file, std::ios::binary);
  if (!in) return;
  const auto fileSize = static_cast<std::uint64_t>(parser->GetFileSize());
  const std::vector<Fragment> fragments =
      fragmentsOf(in, static_cast<std::uint64_t>(parser->GetFileOffset()), fileSize);
  // Each frame: its first fragment and those up to the next that starts a frame.
  std::vector<std::size_t> starts;
  for (std::size_t f = 0; f < fragments.size(); ++f) {
    if (static_cast<long long>(starts.size()) >= frames) break;
    if (f == 0 || static_cast<long long>(fragments.size()) == frames ||
        startsFrame(codec, readSpan(in, fragments, f, f + 1, 12)))
      starts.push_back(f);
  }
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const std::size_t end = k + 1 < starts.size() ? starts[k + 1] : fragments.size();
    std::uint64_t frameBytes = 0;
    for (std::size_t f = starts[k]; f < end; ++f) frameBytes += fragments[f].length;
    // Most headers end within 4 KiB; large application segments (an ICC profile) need more.
    FrameCheck check;
    for (const std::size_t want : {std::size_t{4096}, std::size_t{256} << 10u}) {
      const std::vector<std::uint8_t> head = readSpan(in, fragments, starts[k], end, want);
      check = checkFrameHeader(codec, layout, head, frameBytes);
      if (check.result != Result::NeedMore || head.size() >= frameBytes) break;
    }
    if (check.result == Result::Mismatch)
      throw InputError(file, "compressed frame " + std::to_string(k + 1) + " of " +
                                 std::to_string(frames) +
                                 " does not match the DICOM header: " + check.problem);
  }
}

}  // namespace mvw::io::detail
