#include "BenchRegister.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "mvw/core/Error.h"
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
  int cases = 7;
};

struct Case {
  glm::dvec3 degrees, mm;
};

// The identity first: it checks the conversion of elastix's parameters (a convention error
// shows there as a TRE of centimetres), then transforms of a few degrees and millimetres
// about every axis, two of 20-25 degrees.
const std::vector<Case> kCases = {
    {{0, 0, 0}, {0, 0, 0}},        {{3, -2, 4}, {5, -8, 6}},     {{-5, 4, -3}, {-10, 6, 12}},
    {{0, 0, 20}, {-6, -12, 5}},    {{12, -10, 14}, {8, 10, -7}}, {{0, 25, 0}, {10, -10, 10}},
    {{-18, 12, 15}, {-12, 8, 14}},
};

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

struct Row {
  double before = 0, oursTre = 0, elastixTre = 0, oursSeconds = 0, elastixSeconds = 0;
  bool converged = false;
};

void runBenchRegister(const BenchRegisterOptions& o) {
  if (!fs::exists(o.elastix)) throw InputError(o.elastix, "elastix is not installed there");
  if (!fs::is_regular_file(o.parameters)) throw InputError(o.parameters, "no such parameter file");
  const Volume ct = io::readVolume(o.ct);
  const PetPhantom phantom(ct);
  const fs::path work = fs::absolute(o.work);
  fs::create_directories(work);
  // Both tools read the same files: the CT as our writer stores it and each PET-like volume.
  const fs::path fixedFile = work / "ct.nii.gz";
  io::writeVolume(ct, fixedFile);

  const int n = std::min<int>(o.cases, static_cast<int>(kCases.size()));
  std::printf(
      "mvw bench register: %s (%d x %d x %d) vs %d PET-like volumes (64 x 64 x 44, 4 mm);"
      " elastix %s -p %s\n",
      o.ct.c_str(), ct.dimensions().x, ct.dimensions().y, ct.dimensions().z, n, o.elastix.c_str(),
      o.parameters.c_str());
  std::printf("%-4s %-20s %-18s %9s %9s %11s %8s %10s %8s\n", "case", "rotation deg", "shift mm",
              "TRE start", "mvw TRE", "elastix TRE", "mvw s", "elastix s", "ratio");
  std::vector<Row> rows;
  for (int c = 0; c < n; ++c) {
    const Case& k = kCases[static_cast<std::size_t>(c)];
    const glm::dmat4 truth = rigidMatrix({k.degrees * kDegree, k.mm}, phantom.centre());
    const fs::path dir = work / ("case" + std::to_string(c));
    fs::remove_all(dir);
    fs::create_directories(dir / "elastix");
    const fs::path movingFile = dir / "pet.nii.gz";
    io::writeVolume(phantom.pet(truth, 1000u + static_cast<unsigned>(c)), movingFile);
    Row row;
    row.before = phantom.meanTre(glm::dmat4(1.0), truth);

    // Ours: read both files and register, as elastix does in its run.
    auto t = Clock::now();
    const RegistrationResult r =
        registerRigid(io::readVolume(fixedFile), io::readVolume(movingFile));
    row.oursSeconds = secondsSince(t);
    row.converged = r.converged;
    row.oursTre = phantom.meanTre(r.transform.movingFromFixed(), truth);

    const std::string command = shellQuoted(o.elastix) + " -f " + shellQuoted(fixedFile) + " -m " +
                                shellQuoted(movingFile) + " -p " + shellQuoted(o.parameters) +
                                " -out " + shellQuoted(dir / "elastix") + " > " +
                                shellQuoted(dir / "elastix.stdout") + " 2>&1";
    t = Clock::now();
    const int rc = std::system(command.c_str());
    row.elastixSeconds = secondsSince(t);
    if (rc != 0)
      throw Error("elastix failed (" + std::to_string(rc) + "): see " +
                  (dir / "elastix.stdout").string());
    row.elastixTre =
        phantom.meanTre(readElastixEuler(dir / "elastix" / "TransformParameters.0.txt"), truth);

    char rotation[64], shift[64];
    std::snprintf(rotation, sizeof rotation, "(%g, %g, %g)", k.degrees.x, k.degrees.y, k.degrees.z);
    std::snprintf(shift, sizeof shift, "(%g, %g, %g)", k.mm.x, k.mm.y, k.mm.z);
    std::printf("%-4d %-20s %-18s %9.2f %9.3f %11.3f %8.2f %10.2f %7.2fx%s\n", c, rotation, shift,
                row.before, row.oursTre, row.elastixTre, row.oursSeconds, row.elastixSeconds,
                row.elastixSeconds / row.oursSeconds, row.converged ? "" : "  (mvw NOT converged)");
    std::fflush(stdout);
    rows.push_back(row);
  }
  double oursMean = 0, oursMax = 0, elMean = 0, elMax = 0, oursTime = 0, elTime = 0;
  int better = 0;
  for (const Row& r : rows) {
    oursMean += r.oursTre / rows.size();
    elMean += r.elastixTre / rows.size();
    oursMax = std::max(oursMax, r.oursTre);
    elMax = std::max(elMax, r.elastixTre);
    oursTime += r.oursSeconds;
    elTime += r.elastixSeconds;
    better += r.oursTre <= r.elastixTre;
  }
  std::printf(
      "summary: %zu pairs; TRE mean/max mvw %.3f/%.3f mm, elastix %.3f/%.3f mm; mvw TRE <= "
      "elastix on %d/%zu; time mvw %.2f s, elastix %.2f s, elastix/mvw %.2fx\n",
      rows.size(), oursMean, oursMax, elMean, elMax, better, rows.size(), oursTime, elTime,
      elTime / oursTime);
}

}  // namespace

void addBenchRegisterCommand(CLI::App& bench) {
  auto o = std::make_shared<BenchRegisterOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "register", "Rigid registration vs elastix on CT / PET-like pairs with known transforms");
  cmd->add_option("ct", o->ct, "CT volume in HU (NIfTI, MetaImage or DICOM)")->required();
  cmd->add_option("--work", o->work, "Folder for the pairs and elastix's output")->required();
  cmd->add_option("--elastix", o->elastix, "elastix executable");
  cmd->add_option("--parameters", o->parameters, "elastix parameter file (rigid, Mattes MI)")
      ->required();
  cmd->add_option("--cases", o->cases,
                  "How many of the known transforms (the first is the identity)")
      ->check(CLI::Range(1, static_cast<int>(kCases.size())));
  cmd->callback([o] { runBenchRegister(*o); });
}

}  // namespace mvw::app
