// Slurm's array limit (batch BatchSlurm): MaxArraySize read from `scontrol show config`, and a
// --tasks larger than it refused before anything is written, saying the limit and the largest
// --tasks allowed.
#include <string>

#include <gtest/gtest.h>

#include "mvw/batch/BatchSlurm.h"
#include "mvw/core/Error.h"

namespace mvw::batch {
namespace {

TEST(BatchSlurm, MaxArraySizeIsReadFromScontrolShowConfig) {
  EXPECT_EQ(parseMaxArraySize("Configuration data as of 2026-12-07T01:00:00\n"
                              "MaxArraySize            = 1001\n"
                              "MaxJobCount             = 10000\n"),
            1001);
  EXPECT_EQ(parseMaxArraySize("MaxJobCount = 10000\n"), 0);
  EXPECT_EQ(parseMaxArraySize("MaxArraySize = lots\n"), 0);
}

TEST(BatchSlurm, TasksBeyondMaxArraySizeAreRefusedWithTheLargestAllowed) {
  EXPECT_NO_THROW(checkSlurmArraySize(5, 5));
  EXPECT_NO_THROW(checkSlurmArraySize(100000, 0));  // the limit unknown: sbatch decides
  try {
    checkSlurmArraySize(6, 5);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(
        m.rfind("--tasks 6: is more than one Slurm array may hold on the Slurm controller", 0), 0u)
        << m;
    EXPECT_NE(m.find("its MaxArraySize is 5 (task ids 0-4); give --tasks 5 or fewer"),
              std::string::npos)
        << m;
  }
}

}  // namespace
}  // namespace mvw::batch
