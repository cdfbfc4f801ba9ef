#include "BenchRegister.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "CliChecks.h"
#include "CommandBody.h"
#include "mvw/core/Error.h"
#include "mvw/core/ExitCode.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/resampling/PetPhantom.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;
using namespace mvw::resampling;
using Clock = std::chrono::steady_clock;

constexpr double kDegree = std::numbers::pi / 180.0;

struct BenchRegisterOptions {
  std::string ct;
  std::string work;
  std::string elastix = "/usr/bin/elastix";
  std::string parameters;
  int cases = 4;                               // per voxel size
  std::vector<double> voxelMm = {2, 4, 5, 6};  // functional voxel sizes
  double noise = 0.1;                          // PetGridOptions::noise
  unsigned seed = 1;                           // of the transforms and the noise
  double maxDegrees = 10.0, maxMm = 10.0;      // range of the random transforms, per axis
};

struct Case {
  glm::dvec3 degrees, mm;
};

// Seeded random rigid transforms, uniform in +-maxDegrees about each axis and +-maxMm along
// each, a fresh set per voxel size (so no one transform is tuned for).
std::vector<Case> randomCases(const BenchRegisterOptions& o, std::size_t voxelIndex) {
  std::mt19937 rng(o.seed * 7919u + static_cast<unsigned>(voxelIndex));
  std::uniform_real_distribution<double> deg(-o.maxDegrees, o.maxDegrees), mm(-o.maxMm, o.maxMm);
  std::vector<Case> cases(static_cast<std::size_t>(o.cases));
  for (Case& c : cases) {
    c.degrees = {deg(rng), deg(rng), deg(rng)};
    c.mm = {mm(rng), mm(rng), mm(rng)};
  }
  return cases;
}

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string shellQuoted(const fs::path& p) {
  std::string s = "'";
  for (char c : p.string()) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return s + "'";
}

// The numbers after `(key` in an elastix parameter file, e.g. (TransformParameters a b c).
std::vector<double> elastixValues(const std::string& text, const std::string& key,
                                  const fs::path& file) {
  const std::string open = "(" + key + " ";
  const auto at = text.find(open);
  if (at == std::string::npos) throw InputError(file, "has no " + key);
  const auto end = text.find(')', at);
  std::istringstream in(text.substr(at + open.size(), end - at - open.size()));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

// elastix's EulerTransform maps fixed points to moving points, x -> R (x - c) + c + t, in
// the physical (LPS) space ITK reads NIfTI into; R = Rz Rx Ry unless ComputeZYX is true
// (then Rz Ry Rx). That is rigidMatrix's convention, so petFromCt = rigidMatrix(p, c).
glm::dmat4 readElastixEuler(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "elastix wrote no transform (see elastix.log next to it)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.find("(Transform \"EulerTransform\")") == std::string::npos)
    throw InputError(file, "is not an EulerTransform");
  if (text.find("(InitialTransformParametersFileName \"NoInitialTransform\")") == std::string::npos)
    throw InputError(file, "chains an initial transform: not supported here");
  const auto p = elastixValues(text, "TransformParameters", file);
  const auto c = elastixValues(text, "CenterOfRotationPoint", file);
  if (p.size() != 6 || c.size() != 3)
    throw InputError(file, "expected 6 parameters and a 3-D centre");
  const glm::dvec3 angles(p[0], p[1], p[2]), centre(c[0], c[1], c[2]);
  if (text.find("(ComputeZYX \"true\")") != std::string::npos) {
    const glm::dmat3 rx = eulerRotation({angles.x, 0, 0}), ry = eulerRotation({0, angles.y, 0}),
                     rz = eulerRotation({0, 0, angles.z});
    glm::dmat4 m(rz * ry * rx);
    m[3] = glm::dvec4(centre - glm::dmat3(m) * centre + glm::dvec3(p[3], p[4], p[5]), 1.0);
    return m;
  }
  return rigidMatrix({angles, {p[3], p[4], p[5]}}, centre);
}

// An estimate's error split in two: the displacement of the head's centre (mm) and the
// residual rotation (degrees about x, y, z, from the antisymmetric part of R_est R_true^T).
// Averaged over cases it shows a tool's bias, which the TRE alone hides.
struct ErrorSplit {
  glm::dvec3 centreMm{0.0}, rotationDeg{0.0};
};

ErrorSplit splitError(const glm::dmat4& estimated, const glm::dmat4& truth,
                      const glm::dvec3& centre) {
  ErrorSplit e;
  e.centreMm =
      glm::dvec3(estimated * glm::dvec4(centre, 1.0)) - glm::dvec3(truth * glm::dvec4(centre, 1.0));
  const glm::dmat3 r = glm::dmat3(estimated) * glm::transpose(glm::dmat3(truth));
  e.rotationDeg =
      glm::dvec3(r[1][2] - r[2][1], r[2][0] - r[0][2], r[0][1] - r[1][0]) * 0.5 / kDegree;
  return e;
}

std::string describe(const ErrorSplit& e) {
  char text[120];
  std::snprintf(text, sizeof text,
                "centre (%+.2f, %+.2f, %+.2f) mm, rotation (%+.2f, %+.2f, %+.2f) deg", e.centreMm.x,
                e.centreMm.y, e.centreMm.z, e.rotationDeg.x, e.rotationDeg.y, e.rotationDeg.z);
  return text;
}

struct Row {
  double before = 0, oursTre = 0, elastixTre = 0, oursSeconds = 0, elastixSeconds = 0;
  ErrorSplit oursError, elastixError;
  bool converged = false;
};

struct Summary {
  double voxelMm = 0, oursMean = 0, oursMax = 0, elMean = 0, elMax = 0, oursTime = 0, elTime = 0;
  ErrorSplit oursBias, elastixBias;  // mean error over the cases
  int better = 0, pairs = 0;
};

Summary summarise(double voxelMm, const std::vector<Row>& rows) {
  Summary s;
  s.voxelMm = voxelMm;
  s.pairs = static_cast<int>(rows.size());
  for (const Row& r : rows) {
    const double share = 1.0 / static_cast<double>(rows.size());
    s.oursBias.centreMm += r.oursError.centreMm * share;
    s.oursBias.rotationDeg += r.oursError.rotationDeg * share;
    s.elastixBias.centreMm += r.elastixError.centreMm * share;
    s.elastixBias.rotationDeg += r.elastixError.rotationDeg * share;
    s.oursMean += r.oursTre / static_cast<double>(rows.size());
    s.elMean += r.elastixTre / static_cast<double>(rows.size());
    s.oursMax = std::max(s.oursMax, r.oursTre);
    s.elMax = std::max(s.elMax, r.elastixTre);
    s.oursTime += r.oursSeconds;
    s.elTime += r.elastixSeconds;
    s.better += r.oursTre <= r.elastixTre;
  }
  return s;
}

// Returns false when mvw's mean TRE is above elastix's at any voxel size.
bool runBenchRegister(const BenchRegisterOptions& o) {
  if (!fs::exists(o.elastix)) throw InputError(o.elastix, "elastix is not installed there");
  if (!fs::is_regular_file(o.parameters)) throw InputError(o.parameters, "no such parameter file");
  const Volume ct = io::readVolume(o.ct);
  const fs::path work = fs::absolute(o.work);
  fs::create_directories(work);
  // Both tools read the same files: the CT as our writer stores it and each PET-like volume.
  const fs::path fixedFile = work / "ct.nii.gz";
  io::writeVolume(ct, fixedFile);

  std::printf(
      "mvw bench register: %s (%d x %d x %d) vs PET-like volumes (FWHM 1.5 voxels, noise %g) "
      "under %d seeded random transforms (+-%g deg, +-%g mm per axis) per voxel size;"
      " elastix %s -p %s\n",
      o.ct.c_str(), ct.dimensions().x, ct.dimensions().y, ct.dimensions().z, o.noise, o.cases,
      o.maxDegrees, o.maxMm, o.elastix.c_str(), o.parameters.c_str());
  std::printf("%-5s %-4s %-22s %-22s %9s %9s %11s %8s %10s %8s\n", "voxel", "case", "rotation deg",
              "shift mm", "TRE start", "mvw TRE", "elastix TRE", "mvw s", "elastix s", "ratio");
  std::vector<Summary> summaries;
  for (std::size_t vi = 0; vi < o.voxelMm.size(); ++vi) {
    const double voxel = o.voxelMm[vi];
    // A scanner that reconstructs on this grid resolves about 1.5 voxels (6 mm at 4 mm).
    const PetPhantom phantom(ct, 1.5 * voxel);
    PetGridOptions grid;
    grid.voxelMm = voxel;
    grid.noise = o.noise;
    const std::vector<Case> cases = randomCases(o, vi);
    std::vector<Row> rows;
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const Case& k = cases[c];
      const glm::dmat4 truth = rigidMatrix({k.degrees * kDegree, k.mm}, phantom.centre());
      char name[64];
      std::snprintf(name, sizeof name, "voxel%g-case%zu", voxel, c);
      const fs::path dir = work / name;
      fs::remove_all(dir);
      fs::create_directories(dir / "elastix");
      const fs::path movingFile = dir / "pet.nii.gz";
      io::writeVolume(
          phantom.pet(truth, o.seed * 1000u + static_cast<unsigned>(100 * vi + c), grid),
          movingFile);
      Row row;
      row.before = phantom.meanTre(glm::dmat4(1.0), truth);

      // Ours: read both files and register, as elastix does in its run.
      auto t = Clock::now();
      const RegistrationResult r =
          registerRigid(io::readVolume(fixedFile), io::readVolume(movingFile));
      row.oursSeconds = secondsSince(t);
      row.converged = r.converged;
      row.oursTre = phantom.meanTre(r.transform.movingFromFixed(), truth);
      row.oursError = splitError(r.transform.movingFromFixed(), truth, phantom.centre());

      const std::string command =
          shellQuoted(o.elastix) + " -f " + shellQuoted(fixedFile) + " -m " +
          shellQuoted(movingFile) + " -p " + shellQuoted(o.parameters) + " -out " +
          shellQuoted(dir / "elastix") + " > " + shellQuoted(dir / "elastix.stdout") + " 2>&1";
      t = Clock::now();
      const int rc = std::system(command.c_str());
      row.elastixSeconds = secondsSince(t);
      if (rc != 0)
        throw Error("elastix failed (" + std::to_string(rc) + "): see " +
                    (dir / "elastix.stdout").string());
      const glm::dmat4 elastix = readElastixEuler(dir / "elastix" / "TransformParameters.0.txt");
      row.elastixTre = phantom.meanTre(elastix, truth);
      row.elastixError = splitError(elastix, truth, phantom.centre());

      char rotation[64], shift[64];
      std::snprintf(rotation, sizeof rotation, "(%.1f, %.1f, %.1f)", k.degrees.x, k.degrees.y,
                    k.degrees.z);
      std::snprintf(shift, sizeof shift, "(%.1f, %.1f, %.1f)", k.mm.x, k.mm.y, k.mm.z);
      std::printf("%-5g %-4zu %-22s %-22s %9.2f %9.3f %11.3f %8.2f %10.2f %7.2fx%s\n", voxel, c,
                  rotation, shift, row.before, row.oursTre, row.elastixTre, row.oursSeconds,
                  row.elastixSeconds, row.elastixSeconds / row.oursSeconds,
                  row.converged ? "" : "  (mvw NOT converged)");
      std::printf("      mvw error:     %s\n      elastix error: %s\n",
                  describe(row.oursError).c_str(), describe(row.elastixError).c_str());
      std::fflush(stdout);
      rows.push_back(row);
    }
    summaries.push_back(summarise(voxel, rows));
  }
  std::printf("\nTRE over %d random transforms per voxel size (noise %g):\n", o.cases, o.noise);
  std::printf("%-8s %-22s %-22s %-12s %-9s %-11s %s\n", "voxel mm", "mvw mean / max mm",
              "elastix mean / max mm", "mvw <= el.", "mvw s", "elastix s", "elastix/mvw time");
  bool ok = true;
  for (const Summary& s : summaries) {
    const bool pass = s.oursMean <= s.elMean;
    ok = ok && pass;
    char ours[32], theirs[32], better[16];
    std::snprintf(ours, sizeof ours, "%.3f / %.3f", s.oursMean, s.oursMax);
    std::snprintf(theirs, sizeof theirs, "%.3f / %.3f", s.elMean, s.elMax);
    std::snprintf(better, sizeof better, "%d/%d", s.better, s.pairs);
    std::printf("%-8g %-22s %-22s %-12s %-9.2f %-11.2f %.2fx%s\n", s.voxelMm, ours, theirs, better,
                s.oursTime, s.elTime, s.elTime / s.oursTime,
                pass ? "" : "  <- mvw's mean TRE is above elastix's");
  }
  std::printf("\nMean error over the cases (a bias; single cases scatter about it):\n");
  for (const Summary& s : summaries)
    std::printf("%-8g mvw     %s\n%-8s elastix %s\n", s.voxelMm, describe(s.oursBias).c_str(), "",
                describe(s.elastixBias).c_str());
  std::printf("%s\n", ok ? "verdict: mvw's mean TRE is at or below elastix's at every voxel size"
                         : "verdict: FAIL: mvw's mean TRE is above elastix's at some voxel size");
  std::fflush(stdout);
  return ok;
}

}  // namespace

void addBenchRegisterCommand(CLI::App& bench) {
  auto o = std::make_shared<BenchRegisterOptions>();
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
    return runBenchRegister(*o) ? kExitSuccess : kExitFailure;
  });
}

}  // namespace mvw::app
