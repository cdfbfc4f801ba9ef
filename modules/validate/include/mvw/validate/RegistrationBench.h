#pragma once
// `mvw bench register`: mvw's rigid registration against elastix on CT / PET-like pairs with
// known transforms (resampling::PetPhantom), per functional voxel size. Both tools read the
// same files; the table gives each case's TRE and time, the summary each voxel size's mean and
// maximum TRE, and the mean error split into the head centre's displacement and a residual
// rotation (a bias the TRE alone hides). A validation bench, not a test: the verdict is a
// comparison, the timings are the machine's.
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mvw::validate {

struct RegistrationBenchOptions {
  std::string ct;  // a CT in HU
  std::string work;
  std::string elastix = "/usr/bin/elastix";
  std::string parameters;                      // elastix's parameter file
  int cases = 4;                               // per voxel size
  std::vector<double> voxelMm = {2, 4, 5, 6};  // functional voxel sizes
  double noise = 0.1;                          // PetGridOptions::noise
  unsigned seed = 1;                           // of the transforms and the noise
  double maxDegrees = 10.0, maxMm = 10.0;      // range of the random transforms, per axis
};

// One known transform: rotation about x, y, z in degrees and shift in mm.
struct BenchCase {
  glm::dvec3 degrees{0.0}, mm{0.0};
};

// Seeded random rigid transforms, uniform in +-maxDegrees about each axis and +-maxMm along
// each, a fresh set per voxel size (so no one transform is tuned for).
std::vector<BenchCase> randomBenchCases(const RegistrationBenchOptions& o, std::size_t voxelIndex);

// elastix's EulerTransform from the text of its TransformParameters file (`file` names it in
// errors), as petFromCt (fixed points to moving points, LPS mm). Throws InputError for another
// transform, an initial transform chained, or parameters that are missing or not 6 + 3.
glm::dmat4 elastixEuler(const std::string& text, const std::filesystem::path& file);
// The same, read from the file; a missing file is an InputError that points at elastix.log.
glm::dmat4 readElastixEuler(const std::filesystem::path& file);

// An estimate's error split in two: the displacement of the head's centre (mm) and the
// residual rotation (degrees about x, y, z, from the antisymmetric part of R_est R_true^T).
struct ErrorSplit {
  glm::dvec3 centreMm{0.0}, rotationDeg{0.0};
};
ErrorSplit splitError(const glm::dmat4& estimated, const glm::dmat4& truth,
                      const glm::dvec3& centre);
// "centre (+0.10, -0.20, +0.00) mm, rotation (+0.01, +0.00, -0.03) deg"
std::string describe(const ErrorSplit& e);

// One case's result.
struct BenchRow {
  double before = 0, oursTre = 0, elastixTre = 0, oursSeconds = 0, elastixSeconds = 0;
  ErrorSplit oursError, elastixError;
  bool converged = false;
};

// One voxel size over its cases.
struct BenchSummary {
  double voxelMm = 0, oursMean = 0, oursMax = 0, elMean = 0, elMax = 0, oursTime = 0, elTime = 0;
  ErrorSplit oursBias, elastixBias;  // mean error over the cases
  int better = 0, pairs = 0;         // cases where mvw's TRE is at or below elastix's, of all
};
BenchSummary summarise(double voxelMm, const std::vector<BenchRow>& rows);

// The tables after the cases: TRE per voxel size, the mean errors and the verdict. Returns
// false when mvw's mean TRE is above elastix's at any voxel size.
bool printBenchSummary(const RegistrationBenchOptions& o,
                       const std::vector<BenchSummary>& summaries, std::ostream& out);

// The whole bench, its table on `out` as each case finishes. Returns false when mvw's mean TRE
// is above elastix's at any voxel size. Throws InputError for a missing elastix or parameter
// file, Error when elastix fails.
bool runRegistrationBench(const RegistrationBenchOptions& o, std::ostream& out);

}  // namespace mvw::validate
