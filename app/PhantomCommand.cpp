#include "PhantomCommand.h"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "CliChecks.h"
#include "mvw/core/VesselPhantom.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/resampling/PetPhantom.h"

namespace mvw::app {

namespace {

struct PhantomOptions {
  std::string output;
  VesselTreeSettings vessels;
};

// `mvw phantom vessels -o FILE`: the synthetic vessel tree of the depth-cued MIP tests.
void runVesselPhantom(const PhantomOptions& o) {
  io::checkVolumeOutput(o.output);
  const VesselTree tree = makeVesselTree(o.vessels);
  io::writeVolume(tree.volume, o.output);
  std::cout << "wrote a vessel tree of " << tree.segments.size() << " segments to " << o.output
            << "\n";
}

struct PetPhantomOptions {
  std::string ct, output;
  std::vector<double> rotateDeg{0, 0, 0}, shiftMm{0, 0, 0};
  unsigned seed = 1;
};

// `mvw phantom pet`: the PET-like test volume of the registration tests, as a file.
void runPetPhantom(const PetPhantomOptions& o) {
  io::checkVolumeOutput(o.output, {o.ct});
  const Volume pet = resampling::petPhantomVolume(
      io::readVolume(o.ct), {o.rotateDeg[0], o.rotateDeg[1], o.rotateDeg[2]},
      {o.shiftMm[0], o.shiftMm[1], o.shiftMm[2]}, o.seed);
  io::writeVolume(pet, o.output);
  std::cout << "wrote a PET-like volume (" << pet.dimensions().x << " x " << pet.dimensions().y
            << " x " << pet.dimensions().z << ") to " << o.output << "\n";
}

}  // namespace

void addPhantomCommand(CLI::App& app) {
  auto ph = std::make_shared<PhantomOptions>();
  CLI::App* phantom = app.add_subcommand("phantom", "Synthetic volumes with known geometry");
  phantom->require_subcommand(1);
  CLI::App* cmd = phantom->add_subcommand(
      "vessels", "Branching tubes of decreasing radius on a dim noisy background");
  cmd->add_option("-o,--output", ph->output, "Output file (.nii, .nii.gz, .mha, .mhd)")->required();
  cmd->add_option("--size", ph->vessels.dimensions.x, "Voxels per side")
      ->check(CLI::Range(16, 512));
  cmd->add_option("--generations", ph->vessels.generations, "Branching generations")
      ->check(CLI::Range(1, 12));
  cmd->add_option("--seed", ph->vessels.seed, "Random seed")->check(nonNegative());
  cmd->add_option("--noise", ph->vessels.noiseSigma, "Noise sigma")->check(CLI::Range(0.0, 1e6));
  cmd->callback([ph] {
    ph->vessels.dimensions = glm::ivec3(ph->vessels.dimensions.x);
    runVesselPhantom(*ph);
  });
  auto pet = std::make_shared<PetPhantomOptions>();
  CLI::App* petCmd =
      phantom->add_subcommand("pet",
                              "A PET-like volume made from a CT (uptake model, 6 mm blur, 4 mm "
                              "grid, noise) under a known rigid transform");
  petCmd->add_option("--ct", pet->ct, "The CT (HU)")->required();
  petCmd->add_option("-o,--output", pet->output, "Output file")->required();
  petCmd
      ->add_option("--rotate", pet->rotateDeg,
                   "Rotation about x, y, z in degrees (ITK Euler order)")
      ->expected(3)
      ->check(CLI::Range(-3600.0, 3600.0));
  petCmd->add_option("--shift", pet->shiftMm, "Translation in mm")
      ->expected(3)
      ->check(CLI::Range(-1e4, 1e4));
  petCmd->add_option("--seed", pet->seed, "Noise seed")->check(nonNegative());
  petCmd->callback([pet] { runPetPhantom(*pet); });
}

}  // namespace mvw::app
