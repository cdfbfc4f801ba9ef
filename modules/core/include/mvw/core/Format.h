#pragma once
// Numbers and quoted text as messages and notes show them.
#include <cstdio>
#include <string>
#include <vector>

namespace mvw {

// %g with `significant` digits: 1e-300 and 1e+300, 0.5 and 2, not 0.000000, 300 digits or
// 0.500000 (std::to_string's %f).
inline std::string shortNumber(double x, int significant = 6) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", significant, x);
  return text;
}

// %f with `decimals` digits after the point: coordinates and sizes in mm, shown to a fixed
// precision whatever their magnitude (12.5 at 1 decimal is 12.5, 100 is 100.0).
inline std::string fixedNumber(double x, int decimals) {
  char text[352];  // %f of DBL_MAX: 309 digits before the point
  std::snprintf(text, sizeof text, "%.*f", decimals, x);
  return text;
}

// "1 instance", "2 instances": a count with its noun, singular for one. `plural` for a noun
// that does not take an "s": countOf(n, "study", "studies"), countOf(n, "series", "series").
inline std::string countOf(long long n, const std::string& noun, const std::string& plural = "") {
  return std::to_string(n) + " " + (n == 1 ? noun : plural.empty() ? noun + "s" : plural);
}

// `text` with each control byte (below 0x20, and 0x7f) written as \xNN: a message that quotes
// a file's bytes cannot move the terminal's cursor, clear it, ring or break into lines. Bytes
// from 0x80 stay as they are (UTF-8 names).
inline std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

// A table cell at most `width` characters: a longer text ends in "..." so a reader sees it was cut.
inline std::string clipped(const std::string& text, std::size_t width) {
  if (text.size() <= width) return text;
  return width <= 3 ? text.substr(0, width) : text.substr(0, width - 3) + "...";
}

// The items with `separator` between them: "auto, linear, nearest" from a list of choices.
inline std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

}  // namespace mvw
