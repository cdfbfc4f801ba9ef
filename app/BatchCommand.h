#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw batch run | report | slurm`: a cohort manifest run study by study (resumable, sharded
// for Slurm array jobs and Kubernetes Indexed Jobs), its report, and the sbatch script.
void addBatchCommand(CLI::App& app);

}  // namespace mvw::app
