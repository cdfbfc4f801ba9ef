#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw batch run | report | slurm`: a cohort manifest run study by study (resumable, sharded
// for Slurm array jobs and Kubernetes Indexed Jobs), its report, and the sbatch script. Each
// study (and each Slurm task) is given the cache and the time-outs in `pacs` that were given to
// the batch command, for study configs naming PACS series.
void addBatchCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
