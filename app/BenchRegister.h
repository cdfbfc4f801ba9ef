#pragma once
#include <CLI/CLI.hpp>

namespace mvw::app {

// `mvw bench register`: our rigid registration against elastix on CT / PET-like pairs with
// known transforms (see tests/bench/register-vs-elastix).
void addBenchRegisterCommand(CLI::App& bench);

}  // namespace mvw::app
