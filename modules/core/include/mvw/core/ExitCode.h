#pragma once
// mvw's exit codes, and the one mapping from an error to its code and message
// (docs/design.md#errors). main and every child process that runs a command's code (the render
// processes of `mvw validate`) end through it, so one failure gives one code wherever it
// happens, and each code means one thing.
#include <exception>
#include <functional>
#include <ostream>

namespace mvw {

inline constexpr int kExitSuccess = 0;
// An internal fault, or a comparison that failed (a validate case, a bench, a cohort study).
inline constexpr int kExitFailure = 1;
// Bad input: a file, config or command line that cannot be used.
inline constexpr int kExitBadInput = 2;
// A server or the network failed (PACS, Slurm); the message names the server.
inline constexpr int kExitServiceFailed = 3;

// The exit code of `error`, after writing its one message (one line) to `err`:
//   ServiceError                        -> 3, "mvw: error: WHAT"
//   InputError                          -> 2, "mvw: error: WHAT"
//   std::filesystem::filesystem_error   -> 2, "mvw: error: PATH: WHY" (a path the user gave
//                                             that the file system refused)
//   any other Error, any std::exception -> 1, "mvw: internal error: WHAT"
//   std::bad_alloc                      -> 1, "mvw: internal error: out of memory"
//   anything else thrown                -> 1, "mvw: internal error: an unknown exception"
// `error` must not be null.
int exitCodeOf(std::exception_ptr error, std::ostream& err);

// What `body` returns, or, when it throws, exitCodeOf(the exception, err).
int runReportingErrors(const std::function<int()>& body, std::ostream& err);

}  // namespace mvw
