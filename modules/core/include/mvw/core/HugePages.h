#pragma once
// Transparent huge pages for the process's large buffers: the second start that turns them on.

namespace mvw {

// Where glibc's malloc does not yet back large blocks with transparent huge pages, sets the
// tunable that makes it (GLIBC_TUNABLES glibc.malloc.hugetlb=1) and starts this program again
// with the same arguments (argv, null-terminated); in that second start, puts the environment
// back as the user had it and returns. Also returns (the program goes on as it is) when
// `worthASecondStart` is false (a run shorter than a second start: the caller knows its
// commands), where the user set the tunable, on other C libraries and systems, in
// secure-execution mode, when run through the dynamic loader, or when the new start fails
// (docs/performance-log.md#start-up).
void restartWithHugePages(char** argv, bool worthASecondStart);

// Whether mvw's command line (argv, null-terminated) names a command that reads volumes, the
// only ones a second start pays for: not `mvw pacs` or `mvw config`, nor --version or --help
// without a command, whose whole run is shorter than a second start
// (docs/performance-log.md#start-up). The command is the first argument that is not an option,
// past the values of the global options --cache, --connect-timeout and --read-timeout.
bool commandReadsVolumes(char** argv);

// The variable that marks the second start and keeps GLIBC_TUNABLES as the user had it ("-":
// unset) meanwhile.
inline constexpr const char* kHugePagesMark = "MVW_GLIBC_TUNABLES_BEFORE";

}  // namespace mvw
