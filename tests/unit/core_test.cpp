#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/core/Frame.h"
#include "mvw/core/Orientation.h"
#include "mvw/core/Suv.h"
#include "mvw/core/Volume.h"

namespace mvw {
namespace {

TEST(Volume, GeometryComesBackFromWorldFromIndex) {
  const glm::dmat3 rot = glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(1, 2, 3)));
  const glm::dvec3 spacing(0.7, 1.1, 3.5), origin(-10.5, 20.25, 7.0);
  Volume v({7, 5, 3}, 1, ScalarType::Int16, makeWorldFromIndex(origin, spacing, rot));
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(v.spacing()[a], spacing[a], 1e-12);
    EXPECT_NEAR(v.origin()[a], origin[a], 1e-12);
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(v.direction()[a][b], rot[a][b], 1e-12);
  }
  // Voxel (2, 1, 1) lies at origin + 2*sx*i_dir + 1*sy*j_dir + 1*sz*k_dir.
  const glm::dvec3 expected = origin + rot[0] * (2 * 0.7) + rot[1] * 1.1 + rot[2] * 3.5;
  const glm::dvec3 got = v.worldFromIndexPoint({2, 1, 1});
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[a], expected[a], 1e-12);
  EXPECT_EQ(v.byteSize(), 7u * 5 * 3 * 2);
}

TEST(Volume, ValuesAndRangeIgnoreNaN) {
  Volume v({3, 2, 2}, 1, ScalarType::Float32, glm::dmat4(1.0));
  v.setValue(0, 0, 0, 0, -4.5);
  v.setValue(2, 1, 1, 0, 12.0);
  v.setValue(1, 1, 0, 0, std::numeric_limits<double>::quiet_NaN());
  const auto [lo, hi] = v.valueRange();
  EXPECT_EQ(lo, -4.5);
  EXPECT_EQ(hi, 12.0);
  EXPECT_EQ(v.value(2, 1, 1), 12.0);
}

TEST(Volume, ConvertedAppliesSlopeAndIntercept) {
  Volume v({2, 1, 1}, 2, ScalarType::Int16, glm::dmat4(1.0));
  v.setValue(1, 0, 0, 1, 100);
  const Volume f = v.converted(ScalarType::Float32, 0.5, -1024);
  EXPECT_EQ(f.scalarType(), ScalarType::Float32);
  EXPECT_FLOAT_EQ(static_cast<float>(f.value(1, 0, 0, 1)), -974.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(f.value(0, 0, 0, 0)), -1024.0f);
}

TEST(Orientation, CodesNameTheSideEachAxisPointsToward) {
  EXPECT_EQ(orientationCode(glm::dmat3(1.0)), "LPS");
  EXPECT_EQ(
      orientationCode(glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1))),
      "RAS");
  // Sagittal slices: columns toward P, rows toward I (downward), slices toward L.
  EXPECT_EQ(
      orientationCode(glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0))),
      "PIL");
  // Coronal with a 10 degree tilt still reads by its dominant axes, and counts as oblique.
  const glm::dmat3 tilted =
      glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(10.0), glm::dvec3(1, 0, 0))) *
      glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
  EXPECT_EQ(orientationCode(tilted), "LIP");
  EXPECT_TRUE(isOblique(tilted));
  EXPECT_FALSE(isOblique(glm::dmat3(1.0)));
}

TEST(Suv, StartDecayCorrectionMatchesHandComputation) {
  // 370 MBq F-18 (T1/2 = 6586.2 s) injected at 10:00:00, series at 11:00:00, 75 kg:
  // dose at series start = 370e6 * 2^(-3600/6586.2) = 253314180.24 Bq,
  // factor = 75000 g / 253314180.24 Bq = 2.96075016e-4; 5000 Bq/ml -> SUVbw 1.48037508.
  PetDose dose{370e6, 6586.2, 75.0, 10 * 3600.0, 11 * 3600.0, "START"};
  const auto factor = suvbwFactor(dose);
  ASSERT_TRUE(factor.has_value());
  EXPECT_NEAR(*factor, 2.960750161260463e-4, 1e-15);
  EXPECT_NEAR(5000 * *factor, 1.4803750806302316, 1e-12);
}

TEST(Suv, ScanAfterMidnightAndAdminAndNone) {
  PetDose wrap{370e6, 6586.2, 75.0, 23.5 * 3600.0, 0.5 * 3600.0, "START"};
  EXPECT_NEAR(*suvbwFactor(wrap), 2.960750161260463e-4, 1e-15);
  PetDose admin{370e6, 6586.2, 75.0, 0, 0, "ADMIN"};
  EXPECT_NEAR(*suvbwFactor(admin), 75000.0 / 370e6, 1e-18);
  std::string why;
  PetDose none{370e6, 6586.2, 75.0, 0, 0, "NONE"};
  EXPECT_FALSE(suvbwFactor(none, &why).has_value());
  EXPECT_NE(why.find("DecayCorrection"), std::string::npos);
  PetDose noWeight{370e6, 6586.2, 0.0, 0, 0, "ADMIN"};
  EXPECT_FALSE(suvbwFactor(noWeight, &why).has_value());
  EXPECT_NE(why.find("PatientWeight"), std::string::npos);
}

// Tags that would make an SUV off by orders of magnitude give none, with the reason; real
// protocols with long or negative intervals keep theirs.
TEST(Suv, ImplausibleTagsGiveNoSuv) {
  std::string why;
  const double f18 = 6586.2, cu64 = 45720.0, h = 3600.0, day = 86400.0;
  // Times of day only: injection 23:59, series 13:02 reads as 13 h later (7.1 F-18 half-lives
  // past midnight): refused. A Cu-64 scan the next morning (20 h, 1.6 half-lives): kept.
  PetDose late{370e6, f18, 75.0, (23 * 60 + 59) * 60.0, (13 * 60 + 2) * 60.0, "START"};
  EXPECT_FALSE(suvbwFactor(late, &why).has_value());
  EXPECT_NE(why.find("half-lives) after the injection, reading its earlier time of day as the "
                     "next day"),
            std::string::npos)
      << why;
  PetDose copper{370e6, cu64, 75.0, 14 * h, 10 * h, "START"};
  ASSERT_TRUE(suvbwFactor(copper).has_value());
  EXPECT_NEAR(*suvbwFactor(copper), 75000.0 / (370e6 * std::exp2(-20 * h / cu64)), 1e-15);
  // A dynamic series starting 30 s before the injection: a negative interval, not 23.99 h.
  PetDose dynamic{370e6, f18, 75.0, 10 * h + 30, 10 * h, "START"};
  ASSERT_TRUE(suvbwFactor(dynamic).has_value());
  EXPECT_NEAR(*suvbwFactor(dynamic), 75000.0 / (370e6 * std::exp2(30 / f18)), 1e-15);
  // With dates: the same times on the same day are 11 h the wrong way round; on consecutive
  // days (Cu-64) 23 h, kept.
  PetDose dated{370e6, f18, 75.0, 100 * day + 23.98 * h, 100 * day + 13.03 * h, "START"};
  dated.timesHaveDates = true;
  EXPECT_FALSE(suvbwFactor(dated, &why).has_value());
  EXPECT_NE(why.find("h before the injection"), std::string::npos) << why;
  PetDose nextDay{370e6, cu64, 75.0, 100 * day + 14 * h, 101 * day + 13 * h, "START"};
  nextDay.timesHaveDates = true;
  EXPECT_TRUE(suvbwFactor(nextDay).has_value());
  PetDose heavy{370e6, f18, 1e30, 0, 0, "ADMIN"};
  EXPECT_FALSE(suvbwFactor(heavy, &why).has_value());
  EXPECT_NE(why.find("PatientWeight"), std::string::npos);
  PetDose hot{1e15, f18, 75.0, 0, 0, "ADMIN"};
  EXPECT_FALSE(suvbwFactor(hot, &why).has_value());
  EXPECT_NE(why.find("RadionuclideTotalDose"), std::string::npos);
  PetDose edge{370e6, f18, 1000.0, 0, 11.9 * h, "START"};  // 1000 kg, 6.5 half-lives: kept
  EXPECT_TRUE(suvbwFactor(edge).has_value());
}

TEST(Suv, ParsesDicomDates) {
  EXPECT_DOUBLE_EQ(*parseDicomDate("19700102"), 86400.0);
  EXPECT_DOUBLE_EQ(*parseDicomDate("19860810") - *parseDicomDate("19860809"), 86400.0);
  EXPECT_FALSE(parseDicomDate("19861310").has_value());
  EXPECT_FALSE(parseDicomDate("1986").has_value());
  EXPECT_FALSE(parseDicomDate("").has_value());
}

TEST(Suv, ParsesDicomTimes) {
  EXPECT_DOUBLE_EQ(*parseDicomTime("101530.5"), 36930.5);
  EXPECT_DOUBLE_EQ(*parseDicomTime("10:15:30"), 36930.0);
  EXPECT_DOUBLE_EQ(*parseDicomTime("1015"), 36900.0);
  EXPECT_FALSE(parseDicomTime("abc").has_value());
  EXPECT_FALSE(parseDicomTime("256000").has_value());
  EXPECT_FALSE(parseDicomTime("").has_value());
}

// What a 4D volume contributes (issue 14 item 8): one frame as stored, or the voxel-wise mean,
// each with a note; a frame the volume does not have is bad input naming the file.
TEST(Frame, OneFrameOrTheMeanWithANoteAndOutOfRangeIsBadInput) {
  Volume v({2, 1, 1}, 3, ScalarType::Int16, glm::dmat4(1.0));
  v.metadata().sourcePath = "fmri.nii.gz";
  for (int f = 0; f < 3; ++f) {
    v.setValue(0, 0, 0, f, 10 * (f + 1));  // 10 20 30
    v.setValue(1, 0, 0, f, -f);            // 0 -1 -2
  }
  const Volume f1 = selectFrame(v, {false, 1});
  EXPECT_EQ(f1.components(), 1);
  EXPECT_EQ(f1.scalarType(), ScalarType::Int16);
  EXPECT_EQ(f1.value(0, 0, 0), 20);
  EXPECT_EQ(f1.value(1, 0, 0), -1);
  ASSERT_FALSE(f1.metadata().notes.empty());
  EXPECT_EQ(f1.metadata().notes.back(), "4D volume of 3 frames: frame 1 is used");
  const Volume mean = selectFrame(v, {true, 0});
  EXPECT_EQ(mean.scalarType(), ScalarType::Float32);
  EXPECT_DOUBLE_EQ(mean.value(0, 0, 0), 20.0);
  EXPECT_DOUBLE_EQ(mean.value(1, 0, 0), -1.0);
  EXPECT_NE(mean.metadata().notes.back().find("mean over all frames"), std::string::npos);
  try {
    selectFrame(v, {false, 3});
    FAIL() << "frame 3 of 3 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "fmri.nii.gz");
    EXPECT_NE(std::string(e.what()).find("3 frames (0 .. 2)"), std::string::npos) << e.what();
  }
  // A 3D volume: frame 0 and the mean are the volume itself, frame 1 is refused.
  const Volume flat({2, 1, 1}, 1, ScalarType::UInt8, glm::dmat4(1.0));
  EXPECT_TRUE(selectFrame(flat, {false, 0}).metadata().notes.empty());
  EXPECT_EQ(selectFrame(flat, {true, 0}).scalarType(), ScalarType::UInt8);
  EXPECT_THROW(selectFrame(flat, {false, 1}), InputError);
  // The command line's spelling.
  EXPECT_TRUE(parseFrameChoice("mean")->mean);
  EXPECT_EQ(parseFrameChoice("12")->index, 12);
  for (const char* bad : {"", "-1", "1.5", "first", "0x1", "9999999999"})
    EXPECT_FALSE(parseFrameChoice(bad).has_value()) << bad;
}

}  // namespace
}  // namespace mvw

TEST(Error, WhyUnreadableSaysWhatThePathIs) {
  namespace fs = std::filesystem;
  const fs::path dir = mvw::test::scratchDir() / "why-unreadable";
  fs::remove_all(dir);
  fs::create_directories(dir / "folder");
  std::ofstream(dir / "file.json") << "{}";
  fs::create_symlink(dir / "gone", dir / "dangling");
  fs::create_symlink(dir / "loop-b", dir / "loop-a");
  fs::create_symlink(dir / "loop-a", dir / "loop-b");
  EXPECT_EQ(mvw::whyUnreadable(dir / "file.json"), "");
  EXPECT_EQ(mvw::whyUnreadable(dir / "absent"), "no such file or directory");
  EXPECT_EQ(mvw::whyUnreadable(dir / "folder"), "is a folder, not a file");
  EXPECT_NE(mvw::whyUnreadable(dir / "dangling").find("symbolic link that leads to nothing"),
            std::string::npos);
  EXPECT_NE(mvw::whyUnreadable(dir / "loop-a").find("symbolic link that leads to nothing"),
            std::string::npos);
  EXPECT_EQ(mvw::whyUnreadable(dir / "file.json" / "below"), "cannot be read: Not a directory");
  try {
    mvw::requireReadable(dir / "folder");
    FAIL() << "no error";
  } catch (const mvw::InputError& e) {
    EXPECT_EQ(e.file(), dir / "folder");
    EXPECT_EQ(e.problem(), "is a folder, not a file");
  }
}
