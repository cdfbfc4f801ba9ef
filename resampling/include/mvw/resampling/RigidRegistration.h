#pragma once
// Rigid (6 degrees of freedom) registration of a moving volume to a fixed one by Mattes
// mutual information: multi-resolution (Gaussian pyramid), a seeded random subset of fixed
// points per level, quasi-Newton (BFGS) ascent on the analytic gradient, with rotation
// scaled to millimetres so one step moves a point near the head's surface about as far as
// the same step of translation does.
//
// Optional extras: a coarse rotation search before the coarsest level (for misalignment of
// tens of degrees, where gradient ascent from the identity ends in a local maximum), and an
// affine (12 degrees of freedom) second stage on the finest levels, started from the rigid
// result.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {

enum class Initialisation {
  Automatic,         // world coordinates when the volumes overlap there, else centre of mass
  WorldCoordinates,  // trust both headers (same frame of reference)
  GeometricCentre,   // align the centres of the two bounding boxes
  CentreOfMass,      // align the intensity centroids
};
std::string toString(Initialisation initialisation);

struct RegistrationOptions {
  // Gaussian sigma per level in mm, coarse to fine; 0 means the volume as it is. Empty:
  // {2r, r, 0} with r the larger voxel size (cube root of the voxel volume) of the two.
  std::vector<double> smoothingMm;
  // Fixed sample points per level (coarse to fine); the last entry repeats for extra levels.
  // The finest level decides the accuracy: on the CT / PET-like test pair 30000 points
  // (0.4 % of the CT's voxels) halve the error of 12000 for the same few iterations, and
  // 100000 keep the sampling noise of MI's optimum below its bias at 5 and 6 mm PET voxels.
  // The points are stratified: one uniform point in each of as many cells of the fixed box.
  std::vector<int> samples = {4000, 6000, 100000};
  // At the finest level (smoothing 0), the finer image, when its voxels are at most 2/3 the
  // size of the coarser one's, is smoothed to sigma = this x the coarser voxel size (less what
  // its own voxels already blur): a sharp CT compared with a PET that resolves 1.5 voxels puts
  // MI's peak off the truth (0.3 degrees on the 5 mm test pair) and its sampled estimate on a
  // flat ridge. 0: compare the images as they are. 0.45 rather than 0.5 since the moving
  // range keeps the hot tail (movingRangeClip): lower mean TRE on 22 of 29 seed x noise x voxel
  // size rows of `mvw bench register`, and 6 mm at noise 0.1 and 0.2 well under elastix.
  double resolutionMatching = 0.45;
  // Fixed sample points keep this x the level's scale (its smoothing sigma, at least the
  // coarser voxel size) away from the fixed image's faces. There the smoothed fixed image is
  // made up (its edge repeated), and a moving image often ends with it (a PET/CT's two
  // volumes span the same slices; the test PET's activity stops where the CT does): MI then
  // pulls the moving image's edge to match. On `mvw bench register` (5 mm PET, noise 0.2) the
  // samples within 5 mm of the CT's inferior face gave 4600 of the 8000 ppm/mm slope of MI
  // along z at the truth; a margin of 0.3 took the mean TRE from 0.53 to 0.45 mm.
  double faceMargin = 0.3;  // 0 (or less): the whole box
  // The moving (functional) image's histogram spans its movingRangeClip and 1 - movingRangeClip
  // quantiles; values beyond count in the edge bins. The fixed image's range leaves out 0.1 %
  // at each end (metal, air). A functional image's hottest 0.1 % is no stray voxel but whole
  // structures (the bench phantom's two lesions at 5 mm), and a range cut below them makes the
  // bins fine against the noise: at noise 0.2 on `mvw bench register` (5 mm) MI's optimum
  // moved +0.46 mm along z from noise 0 with a cut at 0.1 %, +0.22 at 0.01 %, +0.08 with the
  // full range (elastix's choice; elastix +0.15). The full range lost at noise 0.1 (6 mm,
  // 0.469 against elastix's 0.457 mm) and lets one hot spike squeeze the tissue into a bin.
  double movingRangeClip = 1e-4;
  // Sample points are drawn in the moving volume instead (the roles swapped, the result
  // inverted) when its box is under half the fixed one's: a thin functional slab in a whole
  // head. Drawn in the larger volume, most points fall outside the slab and the ones inside
  // change as it turns, and MI rewards tilting it over other anatomy: the real T1 -> relative
  // CBF pair (12 slices, 66 mm) came out 10 degrees from its header's alignment, which the
  // T2 -> CBF (0.9 degrees) and T1 -> T2 (1.7 degrees) registrations of the same session
  // confirm to within 2 degrees.
  bool samplePointsInSmallerVolume = true;
  // The rigid stage runs this many times, each with its own sample points on every level
  // (seeds seed, seed + 7919, ...), and the parameters of the runs are averaged. One run's
  // result depends on its points, at the finest level (MI's estimate) and through where the
  // coarser levels leave it on the finest level's flat ridge: on `mvw bench register` (the
  // same CT, so the same points, in every pair) one run had 1, 3 and 8 of the 32 seed x noise
  // x voxel size rows above elastix with three sampling seeds; 4 runs averaged had none, at
  // 1.6-1.8 x the time. Averaging 4 or 8 climbs of the finest level alone (its points only)
  // still left 1-2 rows above. Averaged are the runs that end within the coarser voxel size
  // of the one with the highest metric (RegistrationResult::runsAveraged). 1: one run.
  int runs = 4;
  int histogramBins = 32;
  int maxIterationsPerLevel = 300;
  double rotationScaleMm = 80.0;  // radians x this = mm: about a head's radius
  double maxStepMm = 4.0;         // first step of the coarsest level, halved per finer level
  double minStepMm = 0.005;       // a level has converged when a step falls below this
  double relaxation = 0.5;        // step factor when a trial step does not raise the metric
  std::uint64_t seed = 20261123;
  Initialisation initialisation = Initialisation::Automatic;
  // Coarse rotation search: every combination of angles -range, -range + step, ..., range
  // about the three axes is scored on the coarsest level; the best few are refined there and
  // the one with the highest metric goes on to the finer levels. Off when range is 0.
  double rotationSearchRangeDeg = 0.0;
  double rotationSearchStepDeg = 30.0;
  int rotationSearchCandidates = 6;
  // Affine second stage (scaling and shear too) on the last affineLevels levels.
  bool affine = false;
  int affineLevels = 2;
  int threads = 0;  // 0: every core
  // Called with one line per finished level (for a terminal); may be empty.
  std::function<void(const std::string&)> progress;
};

struct LevelReport {
  std::string stage = "rigid";  // "rigid" or "affine"
  double smoothingMm = 0.0;
  glm::ivec3 fixedDimensions{0};
  glm::ivec3 movingDimensions{0};
  int samples = 0;
  int validSamples = 0;      // at the end of the level
  int iterations = 0;        // metric evaluations after the first
  int rejectedSteps = 0;     // steps that lowered the metric, undone
  double metricStart = 0.0;  // mutual information, nats
  double metricEnd = 0.0;
  double finalStepMm = 0.0;
  bool converged = false;  // the step fell below minStepMm before maxIterationsPerLevel
  double seconds = 0.0;
};

struct RegistrationResult {
  Transform transform;  // fixedFromMoving (anatomicalFromFunctional); centre = rotation centre
  // The rigid stage's result, movingFromFixed about transform.centre(); with `affine` the
  // transform is the affine stage's (a general matrix), these stay the rigid start of it.
  RigidParameters parameters;
  bool affine = false;  // the transform comes from the affine stage
  // The angles (radians) the rotation search led to on the coarsest level, and how many
  // rotations it scored; 0: no search.
  glm::dvec3 searchAngles{0.0};
  int searchedRotations = 0;
  Initialisation initialisation = Initialisation::Automatic;  // the one used
  glm::dvec3 initialTranslationMm{0.0};
  // Rigid levels (each summed or averaged over the runs: iterations and seconds summed, the
  // metric averaged, converged in every run), then the affine ones.
  std::vector<LevelReport> levels;
  int runs = 1;          // rigid runs (RegistrationOptions::runs)
  int runsAveraged = 1;  // of them, those within the coarser voxel size of the best one
  int iterations = 0;
  bool converged = false;  // the finest level converged
  double seconds = 0.0;
  // The sample points lay in the moving volume (RegistrationOptions::
  // samplePointsInSmallerVolume); `levels` keep each volume's own dimensions.
  bool samplesInMoving = false;
};

// Bad input (an empty, 2-D or constant volume, NaNs, no overlap after initialisation, an
// optimiser that drifts out of the moving volume, or an affine stage that collapses it)
// throws mvw::InputError naming the volume's source file.
RegistrationResult registerRigid(const Volume& fixed, const Volume& moving,
                                 const RegistrationOptions& options = {});

}  // namespace mvw::resampling
