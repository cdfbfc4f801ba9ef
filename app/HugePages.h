#pragma once
// Transparent huge pages for the process's large buffers (HugePages.cpp).

namespace mvw::app {

// Where glibc's malloc does not yet back large blocks with transparent huge pages, sets the
// tunable that makes it (GLIBC_TUNABLES glibc.malloc.hugetlb=1) and starts this program again
// with the same arguments; returns (and the program goes on as it is) where it is set already,
// on other C libraries and systems, or when the new start fails.
void restartWithHugePages(char** argv);

}  // namespace mvw::app
