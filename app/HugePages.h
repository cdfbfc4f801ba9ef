#pragma once
// Transparent huge pages for the process's large buffers (HugePages.cpp).

namespace mvw::app {

// Where glibc's malloc does not yet back large blocks with transparent huge pages, sets the
// tunable that makes it (GLIBC_TUNABLES glibc.malloc.hugetlb=1) and starts this program again
// with the same arguments; in that second start, puts the environment back as the user had
// it and returns. Also returns (the program goes on as it is) where the user set the tunable,
// on other C libraries and systems, in secure-execution mode, when run through the dynamic
// loader, or when the new start fails. Only for the commands that read volumes: not for
// `mvw pacs`, `mvw config`, nor --version or --help without a command, whose whole run is
// shorter than a second start (docs/performance-log.md#start-up).
void restartWithHugePages(char** argv);

// Whether the command line (argv, null-terminated) names a command that reads volumes, the
// only ones a second start pays for.
bool readsVolumes(char** argv);

}  // namespace mvw::app
