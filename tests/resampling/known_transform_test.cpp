// Rigid and affine registration against a known truth (issue 3), on a PET-like volume made
// from the real cranium CT: TRE under 1 mm, and what each option buys. Slow (10-30 s a test),
// so the suite has its own file; registerRigid's refusals are rigid_registration_test.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/resampling/PetPhantom.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The cranium CT and a PET-like volume made from it (PetPhantom, shared with `mvw bench
// register`): uptake from HU plus two hot spheres, blurred to ~6 mm FWHM, read onto a 4 mm
// grid under a known rigid transform, with seeded count-like noise.
class KnownTransform : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ct_ = new Volume(io::readVolume(test::sampleData("cranium/cranium.nii.gz")));
    phantom_ = new PetPhantom(*ct_);
    centre_ = phantom_->centre();
  }
  static void TearDownTestSuite() {
    delete ct_;
    delete phantom_;
    ct_ = nullptr;
    phantom_ = nullptr;
  }

  static Volume makePet(const glm::dmat4& movingFromFixed, unsigned seed, bool followHead = false) {
    return phantom_->pet(movingFromFixed, seed, followHead);
  }

  static double meanTre(const glm::dmat4& estimated, const glm::dmat4& truth) {
    EXPECT_GT(phantom_->lattice().size(), 500u);
    return phantom_->meanTre(estimated, truth);
  }

  static Volume* ct_;
  static PetPhantom* phantom_;
  static glm::dvec3 centre_;
};

Volume* KnownTransform::ct_ = nullptr;
PetPhantom* KnownTransform::phantom_ = nullptr;
glm::dvec3 KnownTransform::centre_{0.0};

TEST_F(KnownTransform, IdentityOnIdenticalInputs) {
  const Volume pet = makePet(glm::dmat4(1.0), 11);
  const auto r = registerRigid(pet, pet);
  const double tre = meanTre(r.transform.movingFromFixed(), glm::dmat4(1.0));
  std::cout << "identity: TRE " << tre << " mm, " << r.iterations << " iterations, " << r.seconds
            << " s\n";
  RecordProperty("tre_mm", std::to_string(tre));
  EXPECT_LT(tre, 0.1);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.initialisation, Initialisation::WorldCoordinates);
}

TEST_F(KnownTransform, RecoversRigidTransformsFromCtToPetLike) {
  struct Case {
    glm::dvec3 degrees, mm;
  };
  const std::vector<Case> cases = {
      {{3, -2, 4}, {5, -8, 6}},      {{-5, 4, -3}, {-10, 6, 12}},  {{2, 6, -5}, {12, 10, -5}},
      {{0, 0, 20}, {-6, -12, 5}},    {{12, -10, 14}, {8, 10, -7}}, {{0, 25, 0}, {10, -10, 10}},
      {{-18, 12, 15}, {-12, 8, 14}}, {{30, 0, 0}, {0, 10, 0}},     {{0, 0, -30}, {15, 0, 0}},
  };
  double worst = 0.0;
  unsigned seed = 100;
  for (const auto& c : cases) {
    const glm::dmat4 truth = rigidMatrix({c.degrees * kDegree, c.mm}, centre_);
    const Volume pet = makePet(truth, ++seed);
    const auto r = registerRigid(*ct_, pet);
    const double tre = meanTre(r.transform.movingFromFixed(), truth);
    const double before = meanTre(glm::dmat4(1.0), truth);
    std::cout << "rotation (" << c.degrees.x << ", " << c.degrees.y << ", " << c.degrees.z
              << ") deg, shift (" << c.mm.x << ", " << c.mm.y << ", " << c.mm.z << ") mm: TRE "
              << before << " -> " << tre << " mm, " << r.iterations << " iterations, " << r.seconds
              << " s, converged " << r.converged << "\n";
    for (const auto& l : r.levels)
      std::cout << "    sigma " << l.smoothingMm << " mm: " << l.iterations << " it, MI "
                << l.metricStart << " -> " << l.metricEnd << ", " << l.seconds << " s\n";
    EXPECT_LT(tre, 1.0) << "rotation " << c.degrees.x << "," << c.degrees.y << "," << c.degrees.z;
    EXPECT_TRUE(r.converged);
    worst = std::max(worst, tre);
  }
  RecordProperty("worst_tre_mm", std::to_string(worst));
}

// The four 5 mm transforms of `mvw bench register` (seed 1): rotation in degrees, shift in mm.
const std::vector<std::pair<glm::dvec3, glm::dvec3>>& benchFiveMmCases() {
  static const std::vector<std::pair<glm::dvec3, glm::dvec3>> cases = {
      {{-4.0, -2.4, 5.4}, {7.9, -2.8, -7.9}},
      {{-0.4, -6.2, -4.7}, {-4.0, -10.0, 8.9}},
      {{-6.0, -0.2, 6.0}, {-2.4, 3.8, -7.0}},
      {{-4.0, 6.1, 1.5}, {5.8, -3.6, -1.0}},
  };
  return cases;
}

// A PET on 5 mm voxels that resolves 1.5 voxels (7.5 mm FWHM), as `mvw bench register` makes
// it, from the bench's four 5 mm transforms. Compared with the sharp CT at full resolution,
// MI peaks about 0.3 degrees (nodding) off the truth and its sampled estimate wanders along a
// flat ridge: mean TRE 0.54 mm with the former defaults (30000 samples, gradient steps),
// 0.58 with the current optimiser and samples but no resolution matching, 0.38 with it; with
// the moving range up to the 99.99th percentile (movingRangeClip) 0.40 without, 0.33 with;
// with four runs averaged (RegistrationOptions::runs), which steadies the estimate on the
// ridge too, 0.36 without, 0.33 with.
TEST_F(KnownTransform, ResolutionMatchingRemovesTheBiasOfACoarsePet) {
  const PetPhantom coarse(*ct_, 7.5);
  PetGridOptions grid;
  grid.voxelMm = 5.0;
  const auto& cases = benchFiveMmCases();
  RegistrationOptions unmatched;
  unmatched.resolutionMatching = 0.0;
  double matchedTre = 0.0, unmatchedTre = 0.0;
  unsigned seed = 1200;
  for (const auto& [degrees, mm] : cases) {
    const glm::dmat4 truth = rigidMatrix({degrees * kDegree, mm}, coarse.centre());
    const Volume pet = coarse.pet(truth, seed++, grid);
    const auto r = registerRigid(*ct_, pet);
    const double tre = coarse.meanTre(r.transform.movingFromFixed(), truth);
    const double plain =
        coarse.meanTre(registerRigid(*ct_, pet, unmatched).transform.movingFromFixed(), truth);
    std::cout << "5 mm PET, rotation (" << degrees.x << ", " << degrees.y << ", " << degrees.z
              << ") deg: TRE " << tre << " mm matched, " << plain << " mm unmatched, " << r.seconds
              << " s\n";
    EXPECT_TRUE(r.converged);
    matchedTre += tre / static_cast<double>(cases.size());
    unmatchedTre += plain / static_cast<double>(cases.size());
  }
  RecordProperty("mean_tre_mm", std::to_string(matchedTre));
  EXPECT_LT(matchedTre, 0.45);
  EXPECT_LT(matchedTre, 0.96 * unmatchedTre);
}

// Mean TRE and mean z error (at the head's centre, in the CT's frame) of the defaults and of
// `other` over the bench's four 5 mm transforms, PET at noise 0.2 (seeds from `seed`).
struct DefaultsAgainst {
  double tre = 0.0, otherTre = 0.0, z = 0.0, otherZ = 0.0;
};
DefaultsAgainst noisyFiveMmPetErrors(const Volume& ct, const RegistrationOptions& other,
                                     unsigned seed) {
  const PetPhantom coarse(ct, 7.5);
  PetGridOptions grid;
  grid.voxelMm = 5.0;
  grid.noise = 0.2;
  const auto& cases = benchFiveMmCases();
  DefaultsAgainst e;
  for (const auto& [degrees, mm] : cases) {
    const glm::dmat4 truth = rigidMatrix({degrees * kDegree, mm}, coarse.centre());
    const Volume pet = coarse.pet(truth, seed++, grid);
    const glm::dmat4 with = registerRigid(ct, pet).transform.movingFromFixed();
    const glm::dmat4 without = registerRigid(ct, pet, other).transform.movingFromFixed();
    auto zError = [&](const glm::dmat4& m) {
      const glm::dvec3 c = coarse.centre();
      return glm::dvec3(glm::inverse(truth) * m * glm::dvec4(c, 1.0)).z - c.z;
    };
    const double n = static_cast<double>(cases.size());
    e.tre += coarse.meanTre(with, truth) / n;
    e.otherTre += coarse.meanTre(without, truth) / n;
    e.z += zError(with) / n;
    e.otherZ += zError(without) / n;
  }
  return e;
}

// The test PET's activity stops where the CT's slices do, as a PET/CT's two volumes end
// together: sample points at the CT's faces see the PET's edge, and MI pulls that edge to
// match (a z bias of +0.5 mm at noise 0.2, from the inferior face). Keeping the sample points
// a fraction of the level's scale from the faces removes part of that pull.
TEST_F(KnownTransform, FaceMarginRemovesThePullOfAMovingEdgeAtTheFixedFaces) {
  RegistrationOptions noMargin;
  noMargin.faceMargin = 0.0;
  const auto e = noisyFiveMmPetErrors(*ct_, noMargin, 1300);
  std::cout << "5 mm PET, noise 0.2: mean TRE " << e.tre << " mm with the face margin, "
            << e.otherTre << " mm without; mean z error " << e.z << " / " << e.otherZ << " mm\n";
  RecordProperty("mean_tre_mm", std::to_string(e.tre));
  // Measured: TRE 0.51 against 0.60 mm, z error +0.40 against +0.49 mm (with the moving
  // range to 99.99 % and resolution matching 0.45: 0.43 against 0.61, +0.29 against +0.46;
  // with 4 runs averaged: 0.40 against 0.55, +0.29 against +0.44).
  EXPECT_LT(std::abs(e.z), 0.9 * std::abs(e.otherZ));
  EXPECT_LT(e.tre, 0.9 * e.otherTre);
}

// A PET's noise grows with its activity. With the moving histogram's range cut at the 99.9th
// percentile (the PET's lesions) the bins are fine against that noise, and the noise moves
// MI's optimum along z; a cut at the 99.99th keeps the lesions in range and most of the bias
// away (movingRangeClip).
TEST_F(KnownTransform, MovingRangeWithTheHotTailKeepsNoiseFromPullingAlongZ) {
  RegistrationOptions narrow;
  narrow.movingRangeClip = 1e-3;
  const auto e = noisyFiveMmPetErrors(*ct_, narrow, 1400);
  std::cout << "5 mm PET, noise 0.2: mean TRE " << e.tre << " mm with the range to 99.99 %, "
            << e.otherTre << " mm to 99.9 %; mean z error " << e.z << " / " << e.otherZ << " mm\n";
  RecordProperty("mean_tre_mm", std::to_string(e.tre));
  // Measured: TRE 0.39 against 0.45 mm, z error +0.26 against +0.35 mm (the same with 4 runs
  // averaged: 0.40 against 0.45, +0.27 against +0.36).
  EXPECT_LT(std::abs(e.z), 0.85 * std::abs(e.otherZ));
  EXPECT_LT(e.tre, 0.95 * e.otherTre);
}

// One run's result depends on its sample points: registered with other sampling seeds, the
// same pair comes out in other places. Four runs averaged (RegistrationOptions::runs) should
// scatter about half as much (four independent runs: 1 / sqrt 4).
TEST_F(KnownTransform, FourRunsAveragedHalveTheScatterOfOneRun) {
  const PetPhantom coarse(*ct_, 7.5);
  PetGridOptions grid;
  grid.voxelMm = 5.0;
  grid.noise = 0.2;
  const auto& [degrees, mm] = benchFiveMmCases()[0];
  const glm::dmat4 truth = rigidMatrix({degrees * kDegree, mm}, coarse.centre());
  const Volume pet = coarse.pet(truth, 1500, grid);
  auto scatterAndTre = [&](int runs) {
    std::vector<glm::dmat4> results;
    double tre = 0.0;
    for (std::uint64_t seed : {11u, 22u, 33u, 44u}) {
      RegistrationOptions o;
      o.seed = seed;
      o.runs = runs;
      const RegistrationResult r = registerRigid(*ct_, pet, o);
      EXPECT_EQ(r.runs, runs);
      EXPECT_EQ(r.runsAveraged, runs);
      results.push_back(r.transform.movingFromFixed());
      tre += coarse.meanTre(results.back(), truth) / 4.0;
    }
    double scatter = 0.0;  // mean distance between two seeds' results over the head
    for (std::size_t a = 0; a < results.size(); ++a)
      for (std::size_t b = a + 1; b < results.size(); ++b)
        scatter += coarse.meanTre(results[a], results[b]) / 6.0;
    return std::pair{scatter, tre};
  };
  const auto [oneScatter, oneTre] = scatterAndTre(1);
  const auto [fourScatter, fourTre] = scatterAndTre(4);
  std::cout << "5 mm PET, noise 0.2, 4 sampling seeds: results " << fourScatter
            << " mm apart with 4 runs averaged, " << oneScatter << " mm with one; mean TRE "
            << fourTre << " / " << oneTre << " mm\n";
  RecordProperty("scatter_mm", std::to_string(fourScatter));
  // Measured: 0.070 against 0.140 mm apart; mean TRE 0.461 against 0.454 mm (this pair's
  // error is mostly the bias both share).
  EXPECT_LT(fourScatter, 0.75 * oneScatter);
  EXPECT_LT(fourTre, oneTre + 0.05);
}

// A functional slab (12 of the PET's 44 slices, 48 mm, as an fMRI or ASL slab covers part of
// a head): its box is under half the CT's, so the sample points are drawn in the slab (the
// roles swapped) and the result comes back inverted, in the caller's roles: the transform,
// the rigid parameters about its centre, and each volume's own dimensions per level.
TEST_F(KnownTransform, AThinSlabIsSampledInItselfAndTheResultComesBackInverted) {
  const glm::dmat4 truth = rigidMatrix({glm::dvec3(3, -4, 5) * kDegree, {4, -6, 5}}, centre_);
  const Volume pet = makePet(truth, 31);
  const glm::ivec3 d = pet.dimensions();
  const int first = d.z / 2 - 6;
  Volume slab({d.x, d.y, 12}, 1, ScalarType::Float32,
              pet.worldFromIndex() * glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, first)));
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i)
        slab.dataAs<float>()[slab.linearIndex(i, j, k)] =
            pet.dataAs<float>()[pet.linearIndex(i, j, k + first)];
  const auto r = registerRigid(*ct_, slab);
  const double tre = meanTre(r.transform.movingFromFixed(), truth);
  RegistrationOptions fixedSide;
  fixedSide.samplePointsInSmallerVolume = false;
  const double fixedTre =
      meanTre(registerRigid(*ct_, slab, fixedSide).transform.movingFromFixed(), truth);
  std::cout << "12-slice slab: TRE " << tre << " mm with the points in the slab, " << fixedTre
            << " mm with them in the CT, " << r.seconds << " s\n";
  RecordProperty("tre_mm", std::to_string(tre));
  EXPECT_TRUE(r.samplesInMoving);
  EXPECT_TRUE(r.converged);
  // Measured 0.67 mm (0.79 with the points in the CT; 4 runs averaged: 0.64, 0.82): the lattice
  // spans the whole head, far beyond the slab. Inverted wrongly, the result would be millimetres
  // off.
  EXPECT_LT(tre, 1.0);
  const glm::dmat4 fromParameters = rigidMatrix(r.parameters, r.transform.centre());
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row)
      EXPECT_NEAR(fromParameters[c][row], r.transform.movingFromFixed()[c][row], 1e-9);
  ASSERT_FALSE(r.levels.empty());
  EXPECT_EQ(r.levels.back().fixedDimensions, ct_->dimensions());
  EXPECT_EQ(r.levels.back().movingDimensions, slab.dimensions());
}

TEST_F(KnownTransform, DifferentFramesOfReferenceStartFromTheCentresOfMass) {
  // The PET's world is 300 mm away (another scanner's origin): no overlap in world
  // coordinates, so the automatic initialisation aligns the centroids first.
  const glm::dmat4 truth = rigidMatrix({glm::dvec3(4, -6, 8) * kDegree, {300, -120, 250}}, centre_);
  const Volume pet = makePet(truth, 21, true);
  const auto r = registerRigid(*ct_, pet);
  const double tre = meanTre(r.transform.movingFromFixed(), truth);
  std::cout << "far frames: TRE " << meanTre(glm::dmat4(1.0), truth) << " -> " << tre << " mm, "
            << toString(r.initialisation) << ", " << r.seconds << " s\n";
  EXPECT_EQ(r.initialisation, Initialisation::CentreOfMass);
  EXPECT_LT(tre, 1.0);
  RegistrationOptions world;
  world.initialisation = Initialisation::WorldCoordinates;
  EXPECT_THROW(registerRigid(*ct_, pet, world), InputError);
}

TEST_F(KnownTransform, SameSeedSameResult) {
  const glm::dmat4 truth = rigidMatrix({glm::dvec3(2, -3, 4) * kDegree, {4, 5, -6}}, centre_);
  const Volume pet = makePet(truth, 5);
  const auto a = registerRigid(*ct_, pet);
  const auto b = registerRigid(*ct_, pet);
  EXPECT_EQ(a.transform.movingFromFixed(), b.transform.movingFromFixed());
  EXPECT_EQ(a.iterations, b.iterations);
}

// A known affine map: the rigid part of a case above composed with small anisotropic
// scaling and shear about the head's centre (a scanner's calibration error, a gantry tilt).
TEST_F(KnownTransform, AffineStageRecoversScalingAndShear) {
  glm::dmat3 a(1.0);
  a[0][0] = 1.05;  // x stretched 5 %
  a[1][1] = 0.96;  // y shrunk 4 %
  a[2][2] = 1.03;
  a[1][0] = 0.04;   // x sheared along y
  a[2][1] = -0.03;  // y sheared along z
  glm::dmat4 linear(a);
  linear[3] = glm::dvec4(centre_ - a * centre_, 1.0);
  const glm::dmat4 truth =
      rigidMatrix({glm::dvec3(4, -3, 5) * kDegree, {6, -5, 8}}, centre_) * linear;
  const Volume pet = makePet(truth, 31);

  const auto rigid = registerRigid(*ct_, pet);
  RegistrationOptions options;
  options.affine = true;
  const auto affine = registerRigid(*ct_, pet, options);
  const double rigidTre = meanTre(rigid.transform.movingFromFixed(), truth);
  const double affineTre = meanTre(affine.transform.movingFromFixed(), truth);
  std::cout << "affine truth: TRE " << meanTre(glm::dmat4(1.0), truth) << " mm at the start, rigid "
            << rigidTre << " mm, rigid + affine " << affineTre << " mm, " << affine.iterations
            << " iterations, " << affine.seconds << " s\n";
  for (const auto& l : affine.levels)
    std::cout << "    " << l.stage << " sigma " << l.smoothingMm << " mm: " << l.iterations
              << " it, MI " << l.metricStart << " -> " << l.metricEnd << "\n";
  RecordProperty("affine_tre_mm", std::to_string(affineTre));
  EXPECT_TRUE(affine.affine);
  EXPECT_FALSE(affine.transform.isRigid());
  EXPECT_LT(affineTre, 1.0);
  // The second stage is what recovers it: a rigid map cannot.
  EXPECT_GT(rigidTre, 2.0 * affineTre);
  EXPECT_EQ(affine.levels.size(), rigid.levels.size() + 2);
  EXPECT_EQ(affine.levels.back().stage, "affine");
}

// Large misalignment: gradient ascent from the identity stops in a local maximum; the coarse
// rotation search finds the basin first.
TEST_F(KnownTransform, RotationSearchRecoversLargeRotations) {
  struct Case {
    glm::dvec3 degrees, mm;
  };
  for (const Case& c : {Case{{0, 0, 75}, {8, -6, 4}}, Case{{-60, 20, 0}, {-5, 10, 6}},
                        Case{{10, -85, 15}, {4, 4, -8}}}) {
    const glm::dmat4 truth = rigidMatrix({c.degrees * kDegree, c.mm}, centre_);
    const Volume pet = makePet(truth, 41);
    RegistrationOptions options;
    options.rotationSearchRangeDeg = 90.0;
    const auto r = registerRigid(*ct_, pet, options);
    const double tre = meanTre(r.transform.movingFromFixed(), truth);
    const double plain = meanTre(registerRigid(*ct_, pet).transform.movingFromFixed(), truth);
    std::cout << "rotation (" << c.degrees.x << ", " << c.degrees.y << ", " << c.degrees.z
              << ") deg: TRE " << meanTre(glm::dmat4(1.0), truth) << " -> " << tre
              << " mm with the search (" << r.searchedRotations << " rotations scored, "
              << r.seconds << " s), " << plain << " mm without\n";
    EXPECT_EQ(r.searchedRotations, 7 * 7 * 7);
    EXPECT_LT(tre, 1.0) << c.degrees.x << "," << c.degrees.y << "," << c.degrees.z;
    EXPECT_TRUE(r.converged);
  }
}

}  // namespace
}  // namespace mvw::resampling
