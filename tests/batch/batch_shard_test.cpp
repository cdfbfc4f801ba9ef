// Shards of a cohort (batch BatchShard): which shard this process runs, from --shard, from
// --shards with Kubernetes' index or from Slurm's array variables, each bad value refused naming
// its source; and N studies dealt over K tasks without overlap or gap.
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mvw/batch/BatchShard.h"
#include "mvw/core/Error.h"

namespace mvw::batch {
namespace {

// An environment of the given variables only.
Environment environmentOf(std::map<std::string, std::string> variables) {
  return [variables](const char* name) {
    const auto it = variables.find(name);
    return it == variables.end() ? std::string() : it->second;
  };
}

std::string refusal(const std::string& shard, int shards,
                    const std::map<std::string, std::string>& variables) {
  try {
    resolveBatchShard(shard, shards, environmentOf(variables));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

BatchManifest manifestOf(int studies) {
  BatchManifest m;
  m.studies.resize(static_cast<std::size_t>(studies));
  for (int i = 0; i < studies; ++i) m.studies[static_cast<std::size_t>(i)].id = std::to_string(i);
  return m;
}

TEST(BatchShard, ResolvesFromOptionsThenKubernetesThenSlurm) {
  const auto resolve = [](const std::string& shard, int shards,
                          const std::map<std::string, std::string>& variables) {
    const BatchShard s = resolveBatchShard(shard, shards, environmentOf(variables));
    return std::to_string(s.index) + "/" + std::to_string(s.count);
  };
  EXPECT_EQ(resolve("", 0, {}), "0/1");  // the whole manifest
  EXPECT_EQ(resolve("2/4", 0, {}), "2/4");
  // --shard wins over the environment.
  EXPECT_EQ(resolve("1/3", 0, {{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "8"}}),
            "1/3");
  EXPECT_EQ(resolve("", 5, {{"JOB_COMPLETION_INDEX", "4"}}), "4/5");
  EXPECT_EQ(resolve("", 0, {{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}), "3/4");
  // An array numbered from 10 (--array=10-13): the index counts from its minimum.
  EXPECT_EQ(resolve("", 0,
                    {{"SLURM_ARRAY_TASK_ID", "12"},
                     {"SLURM_ARRAY_TASK_MIN", "10"},
                     {"SLURM_ARRAY_TASK_COUNT", "4"}}),
            "2/4");
}

TEST(BatchShard, RefusesBadValuesNamingTheirSource) {
  EXPECT_EQ(refusal("4/4", 0, {}),
            "--shard: gives shard 4 of 4: I must be 0 to N-1 and N at least 1");
  EXPECT_EQ(refusal("0/0", 0, {}),
            "--shard: gives shard 0 of 0: I must be 0 to N-1 and N at least 1");
  EXPECT_EQ(refusal("x", 0, {}), "--shard: is 'x', not I/N (e.g. 0/4)");
  EXPECT_EQ(refusal("a/2", 0, {}), "--shard's I: is 'a', not a whole number from 0 to 1000000");
  EXPECT_EQ(refusal("1/", 0, {}), "--shard's N: is '', not a whole number from 0 to 1000000");
  EXPECT_EQ(refusal("-1/2", 0, {}), "--shard's I: is '-1', not a whole number from 0 to 1000000");
  EXPECT_EQ(refusal("", 2, {}),
            "--shards: needs JOB_COMPLETION_INDEX (a Kubernetes Indexed Job sets it)");
  EXPECT_EQ(refusal("", 2, {{"JOB_COMPLETION_INDEX", "7"}}),
            "JOB_COMPLETION_INDEX: gives shard 7 of 2: I must be 0 to N-1 and N at least 1");
  EXPECT_EQ(refusal("", 0, {{"SLURM_ARRAY_TASK_ID", "1"}}),
            "SLURM_ARRAY_TASK_COUNT: is not set, but SLURM_ARRAY_TASK_ID is");
  EXPECT_EQ(refusal("", 0, {{"SLURM_ARRAY_TASK_ID", "1x"}, {"SLURM_ARRAY_TASK_COUNT", "2"}}),
            "SLURM_ARRAY_TASK_ID: is '1x', not a whole number from 0 to 1000000");
}

TEST(BatchShard, DealsNStudiesOverKTasksWithoutOverlap) {
  for (const int n : {1, 7, 10, 100}) {
    const BatchManifest m = manifestOf(n);
    for (const int k : {1, 2, 3, 4, 16}) {
      std::multiset<std::string> seen;
      for (int i = 0; i < k; ++i) {
        const std::vector<const BatchStudy*> mine = shardStudies(m, {i, k});
        // Every k-th study from the i-th, in manifest order: sizes differ by at most one.
        const std::size_t expected = static_cast<std::size_t>(n / k + (i < n % k ? 1 : 0));
        ASSERT_EQ(mine.size(), expected) << n << " studies, shard " << i << "/" << k;
        for (std::size_t j = 0; j < mine.size(); ++j) {
          EXPECT_EQ(mine[j], &m.studies[static_cast<std::size_t>(i) + j * k]);
          EXPECT_TRUE(inShard(static_cast<std::size_t>(i) + j * k, {i, k}));
          seen.insert(mine[j]->id);
        }
      }
      // Together the shards are the manifest, each study once.
      EXPECT_EQ(seen.size(), static_cast<std::size_t>(n));
      EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(),
                static_cast<std::size_t>(n));
    }
  }
  EXPECT_EQ(shardStudies(manifestOf(10), {1, 3}).front()->id, "1");
  EXPECT_EQ(shardStudies(manifestOf(10), {1, 3}).back()->id, "7");
}

}  // namespace
}  // namespace mvw::batch
