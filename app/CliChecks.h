#pragma once
// Sign checks for number options whose messages state the rule: CLI11's PositiveNumber and
// NonNegativeNumber are ranges up to DBL_MAX, which their messages print in 309 digits.
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>

namespace mvw::app {

inline CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) {
        return std::strtod(text.c_str(), nullptr) > 0 ? std::string()
                                                      : "must be positive, not '" + text + "'";
      },
      "POSITIVE");
}

inline CLI::Validator nonNegative() {
  return CLI::Validator(
      [](std::string& text) {
        return std::strtod(text.c_str(), nullptr) >= 0 ? std::string()
                                                       : "must be 0 or more, not '" + text + "'";
      },
      "NONNEGATIVE");
}

// A text option given as "" (e.g. --series "" would match every series, --frame "" read as no
// choice): refused rather than taken as the option left out.
inline CLI::Validator nonEmpty() {
  return CLI::Validator(
      [](std::string& text) { return text.empty() ? std::string("must not be empty") : ""; },
      "TEXT");
}

}  // namespace mvw::app
