// ExitCode (core): exitCodeOf, the one mapping from an error to mvw's exit code and message, for
// every kind of error main and the child processes meet (README "Exit codes").
#include <filesystem>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

#include "mvw/core/Error.h"
#include "mvw/core/ExitCode.h"

namespace mvw {
namespace {

struct Said {
  int code;
  std::string message;
};

template <class E>
Said said(const E& error) {
  std::ostringstream err;
  const int code = exitCodeOf(std::make_exception_ptr(error), err);
  return {code, err.str()};
}

TEST(ExitCode, EachErrorHasItsCodeAndOneMessage) {
  const Said server = said(ServiceError("dicom://PACS@127.0.0.1:9: connection refused"));
  EXPECT_EQ(server.code, kExitServiceFailed);
  EXPECT_EQ(server.code, 3);
  EXPECT_EQ(server.message, "mvw: error: dicom://PACS@127.0.0.1:9: connection refused\n");

  const Said input = said(InputError("study.json", "is bad"));
  EXPECT_EQ(input.code, kExitBadInput);
  EXPECT_EQ(input.code, 2);
  EXPECT_EQ(input.message, "mvw: error: study.json: is bad\n");

  const Said files =
      said(std::filesystem::filesystem_error("cannot create", std::filesystem::path("/out/x"),
                                             std::make_error_code(std::errc::permission_denied)));
  EXPECT_EQ(files.code, 2);
  EXPECT_EQ(files.message, "mvw: error: /out/x: Permission denied\n");

  const Said internal = said(Error("a shader did not link"));
  EXPECT_EQ(internal.code, kExitFailure);
  EXPECT_EQ(internal.code, 1);
  EXPECT_EQ(internal.message, "mvw: internal error: a shader did not link\n");

  const Said memory = said(std::bad_alloc());
  EXPECT_EQ(memory.code, 1);
  EXPECT_EQ(memory.message, "mvw: internal error: out of memory\n");

  const Said other = said(std::logic_error("vector::at"));
  EXPECT_EQ(other.code, 1);
  EXPECT_EQ(other.message, "mvw: internal error: vector::at\n");

  const Said unknown = said(42);
  EXPECT_EQ(unknown.code, 1);
  EXPECT_EQ(unknown.message, "mvw: internal error: an unknown exception\n");
}

TEST(ExitCode, RunReportingErrorsGivesTheBodysCodeOrItsErrors) {
  std::ostringstream err;
  EXPECT_EQ(runReportingErrors([] { return 0; }, err), kExitSuccess);
  EXPECT_EQ(runReportingErrors([] { return 1; }, err), 1);
  EXPECT_EQ(err.str(), "");  // a code the body returns was said by the body, if at all
  EXPECT_EQ(runReportingErrors([]() -> int { throw ServiceError("http://pacs: HTTP 503"); }, err),
            3);
  EXPECT_EQ(err.str(), "mvw: error: http://pacs: HTTP 503\n");
}

}  // namespace
}  // namespace mvw
