#pragma once
// `mvw batch slurm`: a Slurm array job whose tasks each run one shard of the manifest
// (`mvw batch run --shard ${SLURM_ARRAY_TASK_ID}/N`), with a log per task; optionally submitted
// with sbatch.
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/core/Error.h"

namespace mvw::batch {

struct SlurmJobOptions {
  std::filesystem::path manifest, out, mvwExecutable;
  int tasks = 1;
  int jobs = 1;           // --jobs of each task, and its --cpus-per-task
  int throttle = 0;       // at most this many tasks at once (the array's %K); 0 = no limit
  std::string partition;  // "" = the cluster's default
  std::string time;       // "" = the partition's default (e.g. 01:00:00)
  std::string mem;        // "" = the partition's default (e.g. 8G)
  // mvw's own options each task's `mvw batch run` is given (--cache, the PACS time-outs).
  std::vector<std::string> mvwOptions;
};

// The sbatch script's text.
std::string slurmScript(const SlurmJobOptions& options);

// Makes OUT/logs, writes OUT/batch.sbatch (slurmScript) atomically and makes it executable;
// returns its path. Throws InputError naming OUT when it cannot be made.
std::filesystem::path writeSlurmScript(const SlurmJobOptions& options);

// MaxArraySize from the text of `scontrol show config` ("MaxArraySize = 1001"); 0 when it does
// not say.
int parseMaxArraySize(const std::string& scontrolConfig);

// The controller's MaxArraySize, asked with `scontrol show config` before submitting; 0 when
// scontrol is missing or cannot reach the controller (sbatch then says what is wrong).
int slurmMaxArraySize();

// Throws InputError naming --tasks (exit 2) when `tasks` array tasks (ids 0..tasks-1) do not fit
// one array of a controller whose MaxArraySize is `maxArraySize` (ids 0..MaxArraySize-1), saying
// the limit and the largest --tasks allowed. The job is refused rather than split into several
// arrays: one job id stays the one thing to watch, cancel and resubmit, and fewer tasks still
// cover every study (each runs a shard). No check when `maxArraySize` is 0 (unknown).
void checkSlurmArraySize(int tasks, int maxArraySize);

// The scheduler could not be reached or refused the job: exit 3, naming the server.
class SchedulerError : public ServiceError {
 public:
  explicit SchedulerError(const std::string& message) : ServiceError(message) {}
};

// Runs `sbatch --parsable script` and returns the job id. Throws InputError when sbatch is not
// installed, SchedulerError (naming the controller from slurm.conf) when it fails.
std::string submitSlurmScript(const std::filesystem::path& script);

}  // namespace mvw::batch
