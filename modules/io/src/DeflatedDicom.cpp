#include "DeflatedDicom.h"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>
#include <zlib.h>

#include "FileChecks.h"
#include "mvw/core/Error.h"

namespace mvw::io::detail {

namespace {

namespace fs = std::filesystem;

constexpr const char* kDeflated = "1.2.840.10008.1.2.1.99";
constexpr const char* kExplicitLittle = "1.2.840.10008.1.2.1";

std::uint16_t u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }
std::uint32_t u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
void put16(std::vector<std::uint8_t>& b, unsigned v) {
  b.push_back(static_cast<std::uint8_t>(v & 0xff));
  b.push_back(static_cast<std::uint8_t>((v >> 8) & 0xff));
}
void put32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xff));
}
bool longLength(const char vr[2]) {
  static const char* kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                "SV", "UC", "UN", "UR", "UT", "UV"};
  for (const char* l : kLong)
    if (vr[0] == l[0] && vr[1] == l[1]) return true;
  return false;
}

struct MetaElement {
  std::uint16_t element;
  char vr[2];
  std::vector<std::uint8_t> value;
};

// Inflates raw deflate (as the standard says) or, failing that, a zlib/gzip-wrapped stream.
std::vector<std::uint8_t> inflateAll(const fs::path& file, const std::uint8_t* in, std::size_t n,
                                     std::size_t maxBytes) {
  for (const int windowBits : {-15, 15 + 32}) {
    z_stream z{};
    if (inflateInit2(&z, windowBits) != Z_OK) break;
    std::vector<std::uint8_t> out;
    z.next_in = const_cast<Bytef*>(in);
    z.avail_in = static_cast<uInt>(n);
    int rc = Z_OK;
    std::uint8_t chunk[1 << 16];
    while (rc == Z_OK) {
      z.next_out = chunk;
      z.avail_out = sizeof chunk;
      rc = inflate(&z, Z_NO_FLUSH);
      out.insert(out.end(), chunk, chunk + (sizeof chunk - z.avail_out));
      if (out.size() > maxBytes) {
        inflateEnd(&z);
        throw InputError(file, "the deflated data set inflates to more than the memory limit");
      }
      if (rc == Z_BUF_ERROR && z.avail_in == 0) break;  // stream ends without its final block
    }
    inflateEnd(&z);
    if (rc == Z_STREAM_END) return out;
  }
  throw InputError(file, "the deflated data set is not a valid deflate stream");
}

std::string uniqueTempName() {
  static std::atomic<unsigned> counter{0};
  return "mvw-inflated-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".dcm";
}

}  // namespace

InflatedDicom::~InflatedDicom() {
  std::error_code ec;
  if (!path_.empty()) fs::remove(path_, ec);
}

std::optional<InflatedDicom> inflateDeflatedDicom(const fs::path& file, std::size_t maxBytes) {
  const std::uintmax_t size = regularFileSize(file);
  if (size < 132 + 12) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  char head[132];
  if (!in.read(head, sizeof head) || std::memcmp(head + 128, "DICM", 4) != 0) return std::nullopt;
  // The meta group (0002,xxxx) is always Explicit VR Little Endian; read at most its first
  // 64 KiB element by element, each length checked against what is there.
  std::vector<std::uint8_t> meta(
      static_cast<std::size_t>(std::min<std::uintmax_t>(size - 132, 1 << 16)));
  in.read(reinterpret_cast<char*>(meta.data()), static_cast<std::streamsize>(meta.size()));
  std::vector<MetaElement> elements;
  std::string syntax;
  std::size_t pos = 0;
  while (pos + 8 <= meta.size() && u16(meta.data() + pos) == 0x0002) {
    MetaElement e;
    e.element = u16(meta.data() + pos + 2);
    e.vr[0] = static_cast<char>(meta[pos + 4]);
    e.vr[1] = static_cast<char>(meta[pos + 5]);
    std::size_t length = 0, header = 8;
    if (longLength(e.vr)) {
      if (pos + 12 > meta.size()) return std::nullopt;
      length = u32(meta.data() + pos + 8);
      header = 12;
    } else {
      length = u16(meta.data() + pos + 6);
    }
    if (length > meta.size() - pos - header) return std::nullopt;  // vtk-dicom reports it
    e.value.assign(meta.begin() + static_cast<long>(pos + header),
                   meta.begin() + static_cast<long>(pos + header + length));
    if (e.element == 0x0010) {
      syntax.assign(e.value.begin(), e.value.end());
      while (!syntax.empty() && (syntax.back() == '\0' || syntax.back() == ' ')) syntax.pop_back();
    }
    elements.push_back(std::move(e));
    pos += header + length;
  }
  if (syntax != kDeflated) return std::nullopt;

  // The rest of the file is the deflated data set.
  in.clear();
  in.seekg(static_cast<std::streamoff>(132 + pos));
  std::vector<std::uint8_t> compressed((std::istreambuf_iterator<char>(in)),
                                       std::istreambuf_iterator<char>());
  const std::vector<std::uint8_t> dataset =
      inflateAll(file, compressed.data(), compressed.size(), maxBytes);

  std::vector<std::uint8_t> group;  // every meta element but the group length, rewritten
  for (auto& e : elements) {
    if (e.element == 0x0000) continue;
    if (e.element == 0x0010) {
      e.value.assign(kExplicitLittle, kExplicitLittle + std::strlen(kExplicitLittle));
      e.value.push_back(0);  // even length
    }
    put16(group, 0x0002);
    put16(group, e.element);
    group.push_back(static_cast<std::uint8_t>(e.vr[0]));
    group.push_back(static_cast<std::uint8_t>(e.vr[1]));
    if (longLength(e.vr)) {
      put16(group, 0);
      put32(group, static_cast<std::uint32_t>(e.value.size()));
    } else {
      put16(group, static_cast<unsigned>(e.value.size()));
    }
    group.insert(group.end(), e.value.begin(), e.value.end());
  }
  std::vector<std::uint8_t> out(head, head + 132);
  put16(out, 0x0002);
  put16(out, 0x0000);
  out.push_back('U');
  out.push_back('L');
  put16(out, 4);
  put32(out, static_cast<std::uint32_t>(group.size()));
  out.insert(out.end(), group.begin(), group.end());
  out.insert(out.end(), dataset.begin(), dataset.end());

  std::optional<InflatedDicom> inflated(std::in_place,
                                        fs::temp_directory_path() / uniqueTempName());
  std::ofstream o(inflated->path(), std::ios::binary | std::ios::trunc);
  if (!o.write(reinterpret_cast<const char*>(out.data()),
               static_cast<std::streamsize>(out.size())) ||
      !o.flush())
    throw Error("cannot write the inflated copy of " + file.string() + " to " +
                inflated->path().string());
  return inflated;
}

}  // namespace mvw::io::detail
