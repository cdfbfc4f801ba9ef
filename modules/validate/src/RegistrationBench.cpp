#include "mvw/validate/RegistrationBench.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <ostream>
#include <random>
#include <sstream>

#include "mvw/core/Error.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/resampling/PetPhantom.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace mvw::validate {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kDegree = std::numbers::pi / 180.0;

// The bench's table lines keep printf's column widths.
[[gnu::format(printf, 1, 2)]] std::string formatted(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string text(static_cast<std::size_t>(std::max(size, 0)) + 1, '\0');
  std::vsnprintf(text.data(), text.size(), format, again);
  va_end(again);
  text.resize(text.size() - 1);
  return text;
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

// elastix's answer for one pair, timed: its run's output goes to dir/elastix.stdout.
glm::dmat4 runElastix(const RegistrationBenchOptions& o, const fs::path& fixedFile,
                      const fs::path& movingFile, const fs::path& dir, double& seconds) {
  const std::string command = shellQuoted(o.elastix) + " -f " + shellQuoted(fixedFile) + " -m " +
                              shellQuoted(movingFile) + " -p " + shellQuoted(o.parameters) +
                              " -out " + shellQuoted(dir / "elastix") + " > " +
                              shellQuoted(dir / "elastix.stdout") + " 2>&1";
  const auto t = Clock::now();
  const int rc = std::system(command.c_str());
  seconds = secondsSince(t);
  if (rc != 0)
    throw Error("elastix failed (" + std::to_string(rc) + "): see " +
                (dir / "elastix.stdout").string());
  return readElastixEuler(dir / "elastix" / "TransformParameters.0.txt");
}

// What one voxel size's cases share: the phantom blurred to it and its grid.
struct VoxelSize {
  std::size_t index = 0;
  double mm = 0.0;
  const resampling::PetPhantom& phantom;
  resampling::PetGridOptions grid;
};

// One case: the PET-like pair written, registered by both tools, its table lines said.
BenchRow runCase(const RegistrationBenchOptions& o, const VoxelSize& v, std::size_t c,
                 const BenchCase& k, const fs::path& work, std::ostream& out) {
  const glm::dmat4 truth = resampling::rigidMatrix({k.degrees * kDegree, k.mm}, v.phantom.centre());
  const fs::path dir = work / formatted("voxel%g-case%zu", v.mm, c);
  fs::remove_all(dir);
  fs::create_directories(dir / "elastix");
  const fs::path fixedFile = work / "ct.nii.gz", movingFile = dir / "pet.nii.gz";
  io::writeVolume(
      v.phantom.pet(truth, o.seed * 1000u + static_cast<unsigned>(100 * v.index + c), v.grid),
      movingFile);
  BenchRow row;
  row.before = v.phantom.meanTre(glm::dmat4(1.0), truth);

  // Ours: read both files and register, as elastix does in its run.
  const auto t = Clock::now();
  const resampling::RegistrationResult r =
      resampling::registerRigid(io::readVolume(fixedFile), io::readVolume(movingFile));
  row.oursSeconds = secondsSince(t);
  row.converged = r.converged;
  row.oursTre = v.phantom.meanTre(r.transform.movingFromFixed(), truth);
  row.oursError = splitError(r.transform.movingFromFixed(), truth, v.phantom.centre());

  const glm::dmat4 elastix = runElastix(o, fixedFile, movingFile, dir, row.elastixSeconds);
  row.elastixTre = v.phantom.meanTre(elastix, truth);
  row.elastixError = splitError(elastix, truth, v.phantom.centre());

  const std::string rotation =
      formatted("(%.1f, %.1f, %.1f)", k.degrees.x, k.degrees.y, k.degrees.z);
  const std::string shift = formatted("(%.1f, %.1f, %.1f)", k.mm.x, k.mm.y, k.mm.z);
  out << formatted("%-5g %-4zu %-22s %-22s %9.2f %9.3f %11.3f %8.2f %10.2f %7.2fx%s\n", v.mm, c,
                   rotation.c_str(), shift.c_str(), row.before, row.oursTre, row.elastixTre,
                   row.oursSeconds, row.elastixSeconds, row.elastixSeconds / row.oursSeconds,
                   row.converged ? "" : "  (mvw NOT converged)")
      << "      mvw error:     " << describe(row.oursError) << "\n"
      << "      elastix error: " << describe(row.elastixError) << "\n";
  out.flush();
  return row;
}

}  // namespace

std::vector<BenchCase> randomBenchCases(const RegistrationBenchOptions& o, std::size_t voxelIndex) {
  std::mt19937 rng(o.seed * 7919u + static_cast<unsigned>(voxelIndex));
  std::uniform_real_distribution<double> deg(-o.maxDegrees, o.maxDegrees), mm(-o.maxMm, o.maxMm);
  std::vector<BenchCase> cases(static_cast<std::size_t>(o.cases));
  for (BenchCase& c : cases) {
    c.degrees = {deg(rng), deg(rng), deg(rng)};
    c.mm = {mm(rng), mm(rng), mm(rng)};
  }
  return cases;
}

// elastix's EulerTransform maps fixed points to moving points, x -> R (x - c) + c + t, in
// the physical (LPS) space ITK reads NIfTI into; R = Rz Rx Ry unless ComputeZYX is true
// (then Rz Ry Rx). That is rigidMatrix's convention, so petFromCt = rigidMatrix(p, c).
glm::dmat4 elastixEuler(const std::string& text, const fs::path& file) {
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
    const glm::dmat3 rx = resampling::eulerRotation({angles.x, 0, 0}),
                     ry = resampling::eulerRotation({0, angles.y, 0}),
                     rz = resampling::eulerRotation({0, 0, angles.z});
    glm::dmat4 m(rz * ry * rx);
    m[3] = glm::dvec4(centre - glm::dmat3(m) * centre + glm::dvec3(p[3], p[4], p[5]), 1.0);
    return m;
  }
  return resampling::rigidMatrix({angles, {p[3], p[4], p[5]}}, centre);
}

glm::dmat4 readElastixEuler(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "elastix wrote no transform (see elastix.log next to it)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return elastixEuler(buffer.str(), file);
}

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
  return formatted("centre (%+.2f, %+.2f, %+.2f) mm, rotation (%+.2f, %+.2f, %+.2f) deg",
                   e.centreMm.x, e.centreMm.y, e.centreMm.z, e.rotationDeg.x, e.rotationDeg.y,
                   e.rotationDeg.z);
}

BenchSummary summarise(double voxelMm, const std::vector<BenchRow>& rows) {
  BenchSummary s;
  s.voxelMm = voxelMm;
  s.pairs = static_cast<int>(rows.size());
  for (const BenchRow& r : rows) {
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

bool printBenchSummary(const RegistrationBenchOptions& o,
                       const std::vector<BenchSummary>& summaries, std::ostream& out) {
  out << formatted("\nTRE over %d random transforms per voxel size (noise %g):\n", o.cases, o.noise)
      << formatted("%-8s %-22s %-22s %-12s %-9s %-11s %s\n", "voxel mm", "mvw mean / max mm",
                   "elastix mean / max mm", "mvw <= el.", "mvw s", "elastix s", "elastix/mvw time");
  bool ok = true;
  for (const BenchSummary& s : summaries) {
    const bool pass = s.oursMean <= s.elMean;
    ok = ok && pass;
    const std::string ours = formatted("%.3f / %.3f", s.oursMean, s.oursMax);
    const std::string theirs = formatted("%.3f / %.3f", s.elMean, s.elMax);
    const std::string better = formatted("%d/%d", s.better, s.pairs);
    out << formatted("%-8g %-22s %-22s %-12s %-9.2f %-11.2f %.2fx%s\n", s.voxelMm, ours.c_str(),
                     theirs.c_str(), better.c_str(), s.oursTime, s.elTime, s.elTime / s.oursTime,
                     pass ? "" : "  <- mvw's mean TRE is above elastix's");
  }
  out << "\nMean error over the cases (a bias; single cases scatter about it):\n";
  for (const BenchSummary& s : summaries)
    out << formatted("%-8g mvw     %s\n%-8s elastix %s\n", s.voxelMm, describe(s.oursBias).c_str(),
                     "", describe(s.elastixBias).c_str());
  out << (ok ? "verdict: mvw's mean TRE is at or below elastix's at every voxel size"
             : "verdict: FAIL: mvw's mean TRE is above elastix's at some voxel size")
      << "\n";
  out.flush();
  return ok;
}

bool runRegistrationBench(const RegistrationBenchOptions& o, std::ostream& out) {
  if (!fs::exists(o.elastix)) throw InputError(o.elastix, "elastix is not installed there");
  if (!fs::is_regular_file(o.parameters)) throw InputError(o.parameters, "no such parameter file");
  const Volume ct = io::readVolume(o.ct);
  const fs::path work = fs::absolute(o.work);
  fs::create_directories(work);
  // Both tools read the same files: the CT as our writer stores it and each PET-like volume.
  io::writeVolume(ct, work / "ct.nii.gz");

  out << formatted(
             "mvw bench register: %s (%d x %d x %d) vs PET-like volumes (FWHM 1.5 voxels, "
             "noise %g) under %d seeded random transforms (+-%g deg, +-%g mm per axis) per "
             "voxel size; elastix %s -p %s\n",
             o.ct.c_str(), ct.dimensions().x, ct.dimensions().y, ct.dimensions().z, o.noise,
             o.cases, o.maxDegrees, o.maxMm, o.elastix.c_str(), o.parameters.c_str())
      << formatted("%-5s %-4s %-22s %-22s %9s %9s %11s %8s %10s %8s\n", "voxel", "case",
                   "rotation deg", "shift mm", "TRE start", "mvw TRE", "elastix TRE", "mvw s",
                   "elastix s", "ratio");
  std::vector<BenchSummary> summaries;
  for (std::size_t vi = 0; vi < o.voxelMm.size(); ++vi) {
    const double voxel = o.voxelMm[vi];
    // A scanner that reconstructs on this grid resolves about 1.5 voxels (6 mm at 4 mm).
    const resampling::PetPhantom phantom(ct, 1.5 * voxel);
    VoxelSize v{.index = vi, .mm = voxel, .phantom = phantom, .grid = {}};
    v.grid.voxelMm = voxel;
    v.grid.noise = o.noise;
    const std::vector<BenchCase> cases = randomBenchCases(o, vi);
    std::vector<BenchRow> rows;
    for (std::size_t c = 0; c < cases.size(); ++c)
      rows.push_back(runCase(o, v, c, cases[c], work, out));
    summaries.push_back(summarise(voxel, rows));
  }
  return printBenchSummary(o, summaries, out);
}

}  // namespace mvw::validate
