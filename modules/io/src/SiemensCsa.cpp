#include "SiemensCsa.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace mvw::io::detail {

namespace {

// Bounds from the format as written by syngo (83 elements in an MR image header): generous
// enough for any real file, small enough that a fuzzed count cannot make the loop long.
constexpr std::uint32_t kMaxElements = 1000;
constexpr std::int32_t kMaxItems = 1000;

class Cursor {
 public:
  Cursor(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::size_t left() const { return size_ - pos_; }
  bool skip(std::size_t n) {
    if (n > left()) return false;
    pos_ += n;
    return true;
  }
  bool u32(std::uint32_t* v) {
    if (left() < 4) return false;
    *v = static_cast<std::uint32_t>(data_[pos_]) |
         static_cast<std::uint32_t>(data_[pos_ + 1]) << 8 |
         static_cast<std::uint32_t>(data_[pos_ + 2]) << 16 |
         static_cast<std::uint32_t>(data_[pos_ + 3]) << 24;
    pos_ += 4;
    return true;
  }
  bool i32(std::int32_t* v) {
    std::uint32_t u = 0;
    if (!u32(&u)) return false;
    std::memcpy(v, &u, 4);
    return true;
  }
  // A NUL-terminated string inside a field of n bytes.
  bool text(std::size_t n, std::string* out) {
    if (n > left()) return false;
    const char* p = reinterpret_cast<const char*>(data_ + pos_);
    const void* nul = std::memchr(p, 0, n);
    out->assign(p, nul ? static_cast<const char*>(nul) - p : n);
    pos_ += n;
    return true;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

}  // namespace

std::optional<CsaHeader> CsaHeader::parse(const std::uint8_t* data, std::size_t size,
                                          std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<CsaHeader> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (!data || size < 16 || std::memcmp(data, "SV10", 4) != 0)
    return fail("not an SV10 (CSA2) header");
  Cursor in(data, size);
  in.skip(8);  // "SV10" and four unused bytes
  std::uint32_t count = 0, unused = 0;
  if (!in.u32(&count) || !in.u32(&unused)) return fail("truncated before the element count");
  if (count == 0 || count > kMaxElements)
    return fail("implausible element count " + std::to_string(count));
  CsaHeader header;
  for (std::uint32_t e = 0; e < count; ++e) {
    std::string name, vr;
    std::int32_t vm = 0, syngoDt = 0, nItems = 0, marker = 0;
    if (!in.text(64, &name) || !in.i32(&vm) || !in.text(4, &vr) || !in.i32(&syngoDt) ||
        !in.i32(&nItems) || !in.i32(&marker))
      return fail("truncated in element " + std::to_string(e));
    if (nItems < 0 || nItems > kMaxItems)
      return fail("element '" + name + "' claims " + std::to_string(nItems) + " items");
    std::vector<std::string> items;
    for (std::int32_t i = 0; i < nItems; ++i) {
      std::int32_t lengths[4] = {};
      for (auto& l : lengths)
        if (!in.i32(&l)) return fail("truncated in an item of '" + name + "'");
      const std::int32_t length = lengths[1];
      if (length < 0 || static_cast<std::size_t>(length) > in.left())
        return fail("an item of '" + name + "' claims " + std::to_string(length) +
                    " bytes, more than the header holds");
      std::string item;
      in.text(static_cast<std::size_t>(length), &item);
      in.skip(std::min<std::size_t>((4 - length % 4) % 4, in.left()));  // 4-byte alignment
      // Items past the value multiplicity are empty padding in syngo's writer.
      if (vm > 0 && i >= vm) continue;
      item = trimmed(item);
      if (length == 0 || item.empty()) continue;
      items.push_back(std::move(item));
    }
    header.elements_[name] = std::move(items);
  }
  return header;
}

const std::vector<std::string>& CsaHeader::items(const std::string& name) const {
  static const std::vector<std::string> none;
  const auto it = elements_.find(name);
  return it == elements_.end() ? none : it->second;
}

std::optional<double> CsaHeader::number(const std::string& name, std::size_t index) const {
  const auto& all = items(name);
  if (index >= all.size()) return std::nullopt;
  const char* s = all[index].c_str();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace mvw::io::detail
