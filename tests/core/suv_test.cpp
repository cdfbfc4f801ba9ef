// SUVbw (core Suv), the unit PET statistics are read in: the decay-corrected factor against
// hand computation, implausible DICOM tags refused with the reason, DICOM dates and times.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "mvw/core/Suv.h"

namespace mvw {
namespace {

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

}  // namespace
}  // namespace mvw
