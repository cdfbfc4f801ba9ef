#pragma once
// Standardised uptake value, body-weight normalised (SUVbw), from the quantities a PET
// DICOM series carries. Kept free of DICOM parsing so the arithmetic can be checked by hand:
//   SUVbw [g/ml] = C [Bq/ml] * weight [g] / dose at the decay-correction reference [Bq]
// With DecayCorrection START the images are decay-corrected to the series start, so the
// injected dose is decayed from injection to that time: D * 2^(-dt / T_half).
// With ADMIN they are corrected to the injection time and the dose is used as is.
// NONE (no decay correction) is refused: it needs per-frame timing and is left as Bq/ml.
#include <optional>
#include <string>

namespace mvw {

struct PetDose {
  double injectedDoseBq = 0.0;        // RadionuclideTotalDose (0018,1074)
  double halfLifeSeconds = 0.0;       // RadionuclideHalfLife (0018,1075)
  double patientWeightKg = 0.0;       // PatientWeight (0010,1030)
  double injectionTimeSeconds = 0.0;  // RadiopharmaceuticalStartTime, seconds after midnight
  double referenceTimeSeconds = 0.0;  // SeriesTime (or AcquisitionTime), seconds after midnight
  std::string decayCorrection;        // DecayCorrection (0054,1102): START, ADMIN, NONE
  // True when both times above carry their dates (seconds since 1970-01-01, from
  // RadiopharmaceuticalStartDateTime and SeriesDate): the interval is then exact, not a time
  // of day that may have wrapped past midnight.
  bool timesHaveDates = false;
};

// Tags beyond these give no SUV (suvbwFactor says which). The interval from injection to series
// start: a series starting up to an hour before the injection is a dynamic scan (negative
// interval); from times of day alone, an earlier series time is read as the next day, believed
// up to 5 half-lives (an F-18 scan after midnight, a Cu-64 scan the next day; not an F-18
// "13 h" that is an injection time after the series time); any interval up to 10 half-lives
// (counts decayed below 0.1 %).
inline constexpr double kMaxInjectedDoseBq = 1e11;
inline constexpr double kMaxPatientWeightKg = 1000.0;
inline constexpr double kMaxEarlySeriesSeconds = 3600.0;
inline constexpr double kMaxHalfLivesAfterMidnight = 5.0;
inline constexpr double kMaxHalfLives = 10.0;

// Multiply Bq/ml by this to get SUVbw; nullopt with `why` filled when it cannot be computed.
std::optional<double> suvbwFactor(const PetDose& dose, std::string* why = nullptr);

// Seconds after midnight from a DICOM TM value "HHMMSS.FFFFFF" (or "HH:MM:SS" of old files).
std::optional<double> parseDicomTime(const std::string& tm);

// Seconds from 1970-01-01 to the start of a DICOM DA value "YYYYMMDD" (nullopt if not one).
std::optional<double> parseDicomDate(const std::string& da);

}  // namespace mvw
