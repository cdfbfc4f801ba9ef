#pragma once
// Which part of a cohort manifest one process runs: the studies whose index modulo count is
// index, dealt in manifest order, so each shard gets every count-th study and the shards of one
// count cover the manifest without overlap.
#include <functional>
#include <string>
#include <vector>

#include "mvw/batch/BatchManifest.h"

namespace mvw::batch {

struct BatchShard {
  int index = 0;
  int count = 1;
};

// An environment variable's value, "" when it is not set (the process's: std::getenv).
using Environment = std::function<std::string(const char* name)>;
std::string processEnvironment(const char* name);

// The shard from `--shard I/N` when given, else from `--shards N` with Kubernetes'
// JOB_COMPLETION_INDEX, else from SLURM_ARRAY_TASK_ID (minus SLURM_ARRAY_TASK_MIN when set) and
// SLURM_ARRAY_TASK_COUNT, else the whole manifest. Throws InputError naming the option or the
// variable when a value is not a whole number, or I is not in 0..N-1.
BatchShard resolveBatchShard(const std::string& shardOption, int shardsOption,
                             const Environment& environment = processEnvironment);

// True when the study at `index` (0-based, in manifest order) is in the shard.
bool inShard(std::size_t index, const BatchShard& shard);

// The shard's studies, in manifest order.
std::vector<const BatchStudy*> shardStudies(const BatchManifest& manifest, const BatchShard& shard);

}  // namespace mvw::batch
