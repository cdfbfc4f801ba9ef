#include "RegisterCommand.h"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "CliChecks.h"
#include "DicomOutput.h"
#include "mvw/output/RegistrationRun.h"
#include "mvw/study/FunctionalPlacement.h"

namespace mvw::app {

namespace {

struct RegisterOptions {
  std::string study;  // a study config: its anatomical (fixed) and functional (moving) volumes
  std::string fixed, moving, output;
  std::string fixedSeries, movingSeries;
  std::string interpolation = "auto";
  std::string initialisation = "auto";
  std::uint64_t seed = resampling::RegistrationOptions{}.seed;
  bool noSuv = false;
  bool affine = false;
  double rotationSearchDeg = 0.0;
  DicomOutputOptions dicom;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

void runRegister(const RegisterOptions& opt, const CLI::App& cmd) {
  output::RegistrationRequest request;
  // STUDY.json, or --fixed and --moving: one of the two. The study's registration settings
  // (study::registrationOptionsOf, as placing the study and the viewer's re-run map them), then
  // the command line's over them.
  if (!opt.study.empty()) {
    for (const char* o : {"--fixed", "--moving", "--fixed-series", "--moving-series"})
      if (cmd.count(o))
        throw CLI::ValidationError(o, std::string("names a volume; the study config ") + opt.study +
                                          " names both: give one or the other");
    if (std::filesystem::path(opt.study).extension() != ".json")
      throw CLI::ValidationError("STUDY", "'" + opt.study +
                                              "' is not a study config (.json): give the "
                                              "volumes with --fixed and --moving");
    request.study = output::loadRegistrationStudy(opt.study, opt.affine, std::cerr);
    request.options = study::registrationOptionsOf(request.study->registration);
  } else if (opt.fixed.empty() || opt.moving.empty()) {
    throw CLI::ValidationError(opt.fixed.empty() ? "--fixed" : "--moving",
                               "is required (or give a study config: mvw register STUDY.json "
                               "-o OUT)");
  }
  // Checked before any heavy work: a wrong -o should not cost a registration.
  checkDicomOutput(opt.dicom, opt.dicom.dicom, opt.output);
  output::checkRegistrationFolder(opt.output);
  request.studyPath = opt.study;
  request.pacs = opt.pacs;
  request.fixed = opt.fixed;
  request.moving = opt.moving;
  request.fixedSeries = opt.fixedSeries;
  request.movingSeries = opt.movingSeries;
  request.suv = !opt.noSuv;
  request.output = opt.output;
  request.interpolation = *output::parseInterpolation(opt.interpolation);
  if (opt.dicom.dicom) request.dicom = opt.dicom.given();
  resampling::RegistrationOptions& options = request.options;
  options.seed = opt.seed;
  options.initialisation = *output::parseInitialisation(opt.initialisation);
  if (opt.affine) options.affine = true;
  if (cmd.count("--rotation-search")) options.rotationSearchRangeDeg = opt.rotationSearchDeg;
  if (::isatty(STDERR_FILENO))
    options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const output::RegistrationOutcome written =
      output::runRegistration(request, std::cout, std::cerr);
  // Once everything is written and in place: the REG and the resampled series.
  if (opt.dicom.dicom) storeDicom(opt.dicom, opt.pacs, written.dicomFiles, opt.output, std::cout);
}

}  // namespace

void addRegisterCommand(CLI::App& app, const pacs::Options& pacs) {
  auto opt = std::make_shared<RegisterOptions>();
  CLI::App* cmd = app.add_subcommand(
      "register",
      "Register a functional volume to an anatomical one (rigid, optionally affine) and resample "
      "it onto its grid; or a study config's functional volume to its anatomical one");
  cmd->add_option("study", opt->study,
                  "Study config (.json): its anatomical (fixed) and functional (moving) volumes "
                  "and its \"registration\" settings (affine, rotation_search_deg); instead of "
                  "--fixed and --moving");
  cmd->add_option("--fixed", opt->fixed,
                  "Anatomical (reference) volume: DICOM folder or file, NIfTI, MetaImage");
  cmd->add_option("--moving", opt->moving, "Functional volume to align");
  cmd->add_option("-o,--output", opt->output, "Output folder (created if missing)")
      ->required()
      ->check(nonEmpty());
  cmd->add_option("--fixed-series", opt->fixedSeries,
                  "DICOM series of the fixed volume: UID, number or description")
      ->check(nonEmpty());
  cmd->add_option("--moving-series", opt->movingSeries, "DICOM series of the moving volume")
      ->check(nonEmpty());
  cmd->add_option("--interpolation", opt->interpolation,
                  "Resampling: auto (nearest for label maps, else linear), linear, nearest, cubic")
      ->check(CLI::IsMember(output::interpolationNames()));
  cmd->add_option("--init", opt->initialisation,
                  "Initialisation: auto, world (headers as they are), centre (bounding boxes), "
                  "mass (centroids)")
      ->check(CLI::IsMember(output::initialisationNames()));
  cmd->add_option("--seed", opt->seed, "Seed of the sample points (same seed, same result)")
      ->check(nonNegative());  // CLI11 would wrap -3 into an unsigned seed
  cmd->add_flag(
      "--affine", opt->affine,
      "After the rigid stage, an affine one (12 degrees of freedom: scaling and shear too)");
  cmd->add_option("--rotation-search", opt->rotationSearchDeg,
                  "Before refining, score rotations up to this many degrees about each axis in "
                  "30-degree steps on the coarsest level (for large misalignment); 0: off")
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_flag("--no-suv", opt->noSuv, "Keep PET values in Bq/ml instead of converting to SUVbw");
  addDicomOptions(*cmd, opt->dicom, true);
  cmd->callback([opt, cmd, &pacs] {
    opt->pacs = pacs;
    runRegister(*opt, *cmd);
  });
}

}  // namespace mvw::app
