#pragma once
// `mvw batch run`: the studies of one shard of a cohort manifest (BatchShard), each as a child
// mvw process (BatchProcess: a crash or hang is that study's failure), J at a time, each into
// OUT/<id>/ atomically. A study works in OUT/.work-<id>-<pid>/ and is renamed to OUT/<id>/ when
// its command has ended (BatchFolders), with OUT/<id>/done.json or OUT/<id>/failed.json
// (BatchRecord): a killed run leaves only work folders, which the next run of that study
// deletes. A done study is skipped while its inputs and its manifest line are unchanged
// (BatchResume, on BatchInputs' checksums, reused from OUT/hashes/ while a file's stat is
// unchanged: BatchHashCache). OUT is listed once per run, whatever the cohort's size.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "mvw/batch/BatchManifest.h"
#include "mvw/batch/BatchShard.h"

namespace mvw::batch {

struct BatchRunOptions {
  std::filesystem::path out;
  BatchShard shard;
  int jobs = 1;
  double timeoutS = 3600.0;             // per study; then it is killed and failed
  std::filesystem::path mvwExecutable;  // what each study runs (the caller's own binary)
  // mvw's own options each study's command ends with (--cache DIR, the PACS time-outs):
  // batchCommand's mvwOptions.
  std::vector<std::string> mvwOptions;
  std::string version;  // mvw's version, recorded in the markers
  bool verify = false;  // hash every input again, trusting no remembered hash
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

}  // namespace mvw::batch
