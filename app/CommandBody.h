#pragma once
// A command's body returns its exit code (mvw/core/ExitCode.h) instead of ending the process:
// the code goes back up to main, which returns it. CLI11 runs a command as a callback that
// returns nothing, while it parses; a code other than 0 leaves that callback as
// CLI::RuntimeError, CLI11's own way for a callback to give the exit code without a message,
// and main returns its code. An exception the body throws goes to main's exitCodeOf as before.
#include <functional>
#include <utility>

#include <CLI/CLI.hpp>

namespace mvw::app {

inline void setCommandBody(CLI::App& command, std::function<int()> body) {
  command.callback([body = std::move(body)] {
    if (const int code = body(); code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace mvw::app
