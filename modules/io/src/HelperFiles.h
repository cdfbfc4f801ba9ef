#pragma once
// Where mvw's own files beside its libraries are looked for (the movie plugin, the decoder
// helper), in order: the environment variable `envVar` (the file itself; when set, the only
// place tried), beside the running executable's prefix (<bin>/../<libdir>/mvw/: an installed or
// relocated mvw, and this build tree's app/ and tests/), beside the prefix of a shared object
// embedding mvw_io (the folder above the nearest lib/ or lib64/ it lies in: the Python module
// installed into <prefix>/lib/python3.11/dist-packages), then the build tree and the install
// prefix this copy of mvw_io was built for (another program embedding the libraries). Each
// place once. (Internal to mvw_io.)
#include <filesystem>
#include <string>
#include <vector>

namespace mvw::io::detail {

std::vector<std::filesystem::path> helperFileCandidates(const char* envVar, const std::string& file,
                                                        const std::filesystem::path& buildPath,
                                                        const std::filesystem::path& installPath);

}  // namespace mvw::io::detail
