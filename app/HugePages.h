#pragma once
// Which commands start a second time for transparent huge pages (mvw/core/HugePages.h).

namespace mvw::app {

// mvw::restartWithHugePages for the commands that read volumes: not for `mvw pacs`, `mvw
// config`, nor --version or --help without a command, whose whole run is shorter than a
// second start (docs/performance-log.md#start-up).
void restartWithHugePages(char** argv);

// Whether the command line (argv, null-terminated) names a command that reads volumes, the
// only ones a second start pays for.
bool readsVolumes(char** argv);

}  // namespace mvw::app
