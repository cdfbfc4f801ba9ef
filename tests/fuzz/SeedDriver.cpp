// Runs a libFuzzer harness over files without libFuzzer, so that every test build (gcc, the
// release and the ASan + UBSan presets) runs the harnesses once over their seeds: the same
// check as `tests/fuzz/run` with -runs=0, without a third (clang) build. Arguments are files or
// folders (their regular files, in name order). Exit 0 when every input ran; a finding ends the
// process as under libFuzzer (abort from the harness, or a sanitizer report), and an input that
// runs longer than 20 s is killed by SIGALRM (libFuzzer's -timeout=20 in tests/fuzz/run).
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::filesystem::path> inputs(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path arg = argv[i];
    if (!std::filesystem::is_directory(arg)) {
      files.push_back(arg);
      continue;
    }
    std::vector<std::filesystem::path> in;
    for (const auto& e : std::filesystem::directory_iterator(arg))
      if (e.is_regular_file()) in.push_back(e.path());
    std::sort(in.begin(), in.end());
    files.insert(files.end(), in.begin(), in.end());
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  const auto files = inputs(argc, argv);
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s FILE_OR_FOLDER... (no input given or found)\n", argv[0]);
    return 2;
  }
  // libFuzzer's first input is the empty one.
  LLVMFuzzerTestOneInput(nullptr, 0);
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: cannot be read\n", file.c_str());
      return 2;
    }
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
    std::fprintf(stderr, "seed %s (%zu bytes)\n", file.c_str(), bytes.size());
    ::alarm(20);
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  ::alarm(0);
  std::printf("%zu inputs ran (and the empty one)\n", files.size());
  return 0;
}
