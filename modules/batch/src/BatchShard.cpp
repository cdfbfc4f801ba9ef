#include "mvw/batch/BatchShard.h"

#include <cerrno>
#include <cstdlib>

#include "mvw/core/Error.h"

namespace mvw::batch {

namespace {

int wholeNumber(const std::string& text, const std::string& what) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < 0 || v > 1000000)
    throw InputError(what, "is '" + text + "', not a whole number from 0 to 1000000");
  return static_cast<int>(v);
}

}  // namespace

std::string processEnvironment(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

BatchShard resolveBatchShard(const std::string& shardOption, int shardsOption,
                             const Environment& env) {
  BatchShard shard;
  std::string from;
  if (!shardOption.empty()) {
    from = "--shard";
    const auto slash = shardOption.find('/');
    if (slash == std::string::npos)
      throw InputError("--shard", "is '" + shardOption + "', not I/N (e.g. 0/4)");
    shard.index = wholeNumber(shardOption.substr(0, slash), "--shard's I");
    shard.count = wholeNumber(shardOption.substr(slash + 1), "--shard's N");
  } else if (shardsOption > 0) {
    from = "JOB_COMPLETION_INDEX";
    if (env("JOB_COMPLETION_INDEX").empty())
      throw InputError("--shards", "needs JOB_COMPLETION_INDEX (a Kubernetes Indexed Job sets it)");
    shard.index = wholeNumber(env("JOB_COMPLETION_INDEX"), "JOB_COMPLETION_INDEX");
    shard.count = shardsOption;
  } else if (!env("SLURM_ARRAY_TASK_ID").empty()) {
    from = "SLURM_ARRAY_TASK_ID";
    shard.index = wholeNumber(env("SLURM_ARRAY_TASK_ID"), "SLURM_ARRAY_TASK_ID");
    if (!env("SLURM_ARRAY_TASK_MIN").empty())
      shard.index -= wholeNumber(env("SLURM_ARRAY_TASK_MIN"), "SLURM_ARRAY_TASK_MIN");
    if (env("SLURM_ARRAY_TASK_COUNT").empty())
      throw InputError("SLURM_ARRAY_TASK_COUNT", "is not set, but SLURM_ARRAY_TASK_ID is");
    shard.count = wholeNumber(env("SLURM_ARRAY_TASK_COUNT"), "SLURM_ARRAY_TASK_COUNT");
  } else {
    return shard;
  }
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
    throw InputError(from, "gives shard " + std::to_string(shard.index) + " of " +
                               std::to_string(shard.count) +
                               ": I must be 0 to N-1 and N at least 1");
  return shard;
}

bool inShard(std::size_t index, const BatchShard& shard) {
  return static_cast<int>(index % static_cast<std::size_t>(shard.count)) == shard.index;
}

std::vector<const BatchStudy*> shardStudies(const BatchManifest& manifest,
                                            const BatchShard& shard) {
  std::vector<const BatchStudy*> mine;
  for (std::size_t i = 0; i < manifest.studies.size(); ++i)
    if (inShard(i, shard)) mine.push_back(&manifest.studies[i]);
  return mine;
}

}  // namespace mvw::batch
