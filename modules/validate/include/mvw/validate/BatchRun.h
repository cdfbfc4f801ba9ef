#pragma once
// `mvw batch run`: the studies of one shard of a cohort manifest, each as a child mvw process
// (`mvw render|stats|register`: a crash or hang is that study's failure), J at a time, each into
// OUT/<id>/ atomically. A study works in OUT/.work-<id>-<pid>/ and is renamed to OUT/<id>/ when
// its command has ended, with OUT/<id>/done.json (the inputs' checksums, the manifest line,
// mvw's version, the outputs' checksums) or OUT/<id>/failed.json (the exit code and the
// message): a killed run leaves only work folders, which the next run of that study deletes.
// A done study is skipped while its inputs and its manifest line are unchanged.
#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "mvw/validate/BatchManifest.h"

namespace mvw::validate {

struct BatchRunOptions {
  std::filesystem::path out;
  BatchShard shard;
  int jobs = 1;
  double timeoutS = 3600.0;             // per study; then it is killed and failed
  std::filesystem::path mvwExecutable;  // what each study runs (the caller's own binary)
  std::string version;                  // mvw's version, recorded in the markers
};

struct BatchRunCounts {
  int done = 0;     // run now and done
  int skipped = 0;  // done before, inputs and line unchanged
  int failed = 0;
  int total = 0;  // the studies of this shard
};

// Progress goes to `progress` as each study ends: "done / failed / left". Throws InputError when
// OUT cannot be made or written, mvw::Error when no child can be started.
BatchRunCounts runBatch(const BatchManifest& manifest, const BatchRunOptions& options,
                        std::ostream& progress);

// What a study's run depends on: SHA-256 of the study config and of every local file it and the
// options name (a folder: every file in it, in name order), keyed by absolute path.
std::map<std::string, std::string> batchInputChecksums(const BatchStudy& study);

// SHA-256 of a file's bytes, lower-case hex. Throws InputError when it cannot be read.
std::string fileSha256(const std::filesystem::path& file);

// The command line (after the executable) that runs `study` with its outputs in `folder`.
std::vector<std::string> batchCommand(const BatchStudy& study, const std::filesystem::path& folder);

}  // namespace mvw::validate
