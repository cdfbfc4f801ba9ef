#include "mvw/core/Error.h"

namespace mvw {

InputError::InputError(const std::filesystem::path& file, const std::string& problem)
    : Error(file.string() + ": " + problem), file_(file), problem_(problem) {}

}  // namespace mvw
