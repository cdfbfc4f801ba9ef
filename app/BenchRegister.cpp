#include "BenchRegister.h"

#include <iostream>
#include <memory>

#include "CliChecks.h"
#include "CommandBody.h"
#include "mvw/core/ExitCode.h"
#include "mvw/validate/RegistrationBench.h"

namespace mvw::app {

void addBenchRegisterCommand(CLI::App& bench) {
  auto o = std::make_shared<validate::RegistrationBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "register",
      "Rigid registration vs elastix on CT / PET-like pairs with known transforms, per "
      "functional voxel size; exit 1 when mvw's mean TRE is above elastix's at any size");
  cmd->add_option("ct", o->ct, "CT volume in HU (NIfTI, MetaImage or DICOM)")->required();
  cmd->add_option("--work", o->work, "Folder for the pairs and elastix's output")->required();
  cmd->add_option("--elastix", o->elastix, "elastix executable");
  cmd->add_option("--parameters", o->parameters, "elastix parameter file (rigid, Mattes MI)")
      ->required();
  cmd->add_option("--cases", o->cases, "Random rigid transforms per voxel size")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--voxel-mm", o->voxelMm, "Functional voxel sizes (isotropic, mm)")
      ->delimiter(',')
      ->check(CLI::Range(1.0, 12.0));
  cmd->add_option("--noise", o->noise, "Noise sigma at uptake 1 (soft tissue; 0.1 by default)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--seed", o->seed, "Seed of the transforms and the noise")->check(nonNegative());
  cmd->add_option("--max-degrees", o->maxDegrees, "Random rotations up to this, per axis")
      ->check(CLI::Range(0.0, 45.0));
  cmd->add_option("--max-mm", o->maxMm, "Random shifts up to this, per axis")
      ->check(CLI::Range(0.0, 50.0));
  setCommandBody(*cmd, [o] {
    // After the table: a failed comparison, as a failing validate case is, not a fault.
    return validate::runRegistrationBench(*o, std::cout) ? kExitSuccess : kExitFailure;
  });
}

}  // namespace mvw::app
