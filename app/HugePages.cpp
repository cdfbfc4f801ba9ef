#include "HugePages.h"

#include <cstring>
#include <initializer_list>

#include "mvw/core/HugePages.h"

namespace mvw::app {

bool readsVolumes(char** argv) {
  // The command is the first argument that is not an option, past the global options' values
  // (main.cpp: --cache, --connect-timeout, --read-timeout).
  for (int i = 1; argv[i]; ++i) {
    const char* a = argv[i];
    if (a[0] == '-') {
      for (const char* valued : {"--cache", "--connect-timeout", "--read-timeout"})
        if (std::strcmp(a, valued) == 0 && argv[i + 1]) ++i;
      continue;
    }
    // Commands that talk to a server or print text: a start is most of their run.
    return std::strcmp(a, "pacs") != 0 && std::strcmp(a, "config") != 0;
  }
  return false;  // --version, --help, or nothing
}

void restartWithHugePages(char** argv) { mvw::restartWithHugePages(argv, readsVolumes(argv)); }

}  // namespace mvw::app
