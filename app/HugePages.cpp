#include "HugePages.h"

#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <unistd.h>
#endif

namespace mvw::app {

// A clinical-size CT lives in three buffers of its size at once while it opens: the reader's
// (VTK), the volume's, and the GL's texture storage (Mesa's llvmpipe). Each faults in 4 KiB
// pages on first touch, and in a virtual machine a fault is dear: for a 512 x 512 x 432 CT the
// faults were a third of the time from a cold process to the first frame (perf: 34 % of
// samples under the page-fault handler). glibc >= 2.35 backs malloc's large blocks with
// transparent huge pages (2 MiB, where the kernel allows them: THP "madvise" or "always")
// when glibc.malloc.hugetlb=1, for every library in the process; the tunable is read once,
// by the dynamic loader at start-up, hence the second start. It took that cold start from
// 2.94-3.16 s to 1.83-1.96 s at the same peak memory (README, "Speed").
void restartWithHugePages(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  constexpr const char* kTunable = "glibc.malloc.hugetlb";
  const char* current = std::getenv("GLIBC_TUNABLES");
  if (current && std::strstr(current, kTunable)) return;  // set, by mvw's first start or a user
  std::string tunables = current && *current ? std::string(current) + ":" : std::string();
  tunables += std::string(kTunable) + "=1";
  if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // The new start failed (no /proc, say): go on in this process, without huge pages.
  if (current)
    setenv("GLIBC_TUNABLES", current, 1);
  else
    unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

}  // namespace mvw::app
