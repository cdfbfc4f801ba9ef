#include "mvw/core/HugePages.h"

#include <climits>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <sys/auxv.h>
#include <unistd.h>
#endif

namespace mvw {

// A clinical-size CT lives in three buffers of its size at once while it opens: the reader's
// (VTK), the volume's, and the GL's texture storage (Mesa's llvmpipe). Each faults in 4 KiB
// pages on first touch, and in a virtual machine a fault is dear: for a 512 x 512 x 432 CT the
// faults were a third of the time from a cold process to the first frame (perf: 34 % of
// samples under the page-fault handler). glibc >= 2.35 backs malloc's large blocks with
// transparent huge pages (2 MiB, where the kernel allows them: THP "madvise" or "always")
// when glibc.malloc.hugetlb=1, for every library in the process; the tunable is read once,
// by the dynamic loader at start-up, hence the second start. It took that cold start from
// 2.94-3.16 s to 1.23-2.29 s at the same peak memory (docs/performance-log.md#huge-pages).
//
// The second start puts the user's GLIBC_TUNABLES back (kept meanwhile in kHugePagesMark,
// which also marks it), so the programs mvw runs (elastix in `mvw bench register`, ffmpeg)
// start as they would without it.
#if defined(__linux__) && defined(__GLIBC__)
namespace {

// GLIBC_TUNABLES as the user had it (nullptr: unset), and no mark.
void putTunablesBack(const char* before) {
  if (before)
    setenv("GLIBC_TUNABLES", before, 1);
  else
    unsetenv("GLIBC_TUNABLES");
  unsetenv(kHugePagesMark);
}

}  // namespace
#endif

void restartWithHugePages(char** argv, bool worthASecondStart) {
#if defined(__linux__) && defined(__GLIBC__)
  constexpr const char* kUnset = "-";                      // GLIBC_TUNABLES was not set
  if (const char* before = std::getenv(kHugePagesMark)) {  // the second start
    putTunablesBack(std::strcmp(before, kUnset) == 0 ? nullptr : before);
    return;
  }
  if (!worthASecondStart) return;
  // Not where the loader ignores tunables (set-user-ID and the like), nor where this process
  // is not the program itself (run through the dynamic loader: /proc/self/exe is the loader).
  if (getauxval(AT_SECURE) != 0 || getauxval(AT_BASE) == 0) return;
  constexpr const char* kTunable = "glibc.malloc.hugetlb";
  const char* current = std::getenv("GLIBC_TUNABLES");
  if (current && std::strstr(current, kTunable)) return;  // a user's choice: keep it
  // The program's own path, so that the new process keeps mvw's name (ps, top, perf).
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return;
  self[n] = '\0';
  const std::string tunables =
      (current && *current ? std::string(current) + ":" : std::string()) + kTunable + "=1";
  if (setenv(kHugePagesMark, current ? current : kUnset, 1) != 0 ||
      setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) {
    putTunablesBack(current);
    return;
  }
  execv(self, argv);
  putTunablesBack(current);  // the new start failed: go on here, without huge pages
#else
  (void)argv;
  (void)worthASecondStart;
#endif
}

bool commandReadsVolumes(char** argv) {
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

}  // namespace mvw
