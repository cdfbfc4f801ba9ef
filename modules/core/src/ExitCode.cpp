#include "mvw/core/ExitCode.h"

#include <filesystem>
#include <new>

#include "mvw/core/Check.h"
#include "mvw/core/Error.h"

namespace mvw {

int exitCodeOf(std::exception_ptr error, std::ostream& err) {
  MVW_CHECK(error != nullptr);
  try {
    std::rethrow_exception(error);
  } catch (const ServiceError& e) {
    // A server that could not be reached or refused: neither the user's input nor mvw's fault.
    err << "mvw: error: " << e.what() << "\n";
    return kExitServiceFailed;
  } catch (const InputError& e) {
    err << "mvw: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const Error& e) {
    err << "mvw: internal error: " << e.what() << "\n";
    return kExitFailure;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the user gave that the file system refused (permissions, a full disk).
    err << "mvw: error: " << e.path1().string() << ": " << e.code().message() << "\n";
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    err << "mvw: internal error: out of memory\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    err << "mvw: internal error: " << e.what() << "\n";
    return kExitFailure;
  } catch (...) {
    err << "mvw: internal error: an unknown exception\n";
    return kExitFailure;
  }
}

int runReportingErrors(const std::function<int()>& body, std::ostream& err) {
  try {
    return body();
  } catch (...) {
    return exitCodeOf(std::current_exception(), err);
  }
}

}  // namespace mvw
