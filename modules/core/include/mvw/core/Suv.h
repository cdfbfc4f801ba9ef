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
};

// Tags beyond these give no SUV (suvbwFactor says which): 100 GBq, 1000 kg, and 12 h between
// injection and series start read from times of day.
inline constexpr double kMaxInjectedDoseBq = 1e11;
inline constexpr double kMaxPatientWeightKg = 1000.0;
inline constexpr double kMaxUptakeSeconds = 12.0 * 3600.0;

// Multiply Bq/ml by this to get SUVbw; nullopt with `why` filled when it cannot be computed.
std::optional<double> suvbwFactor(const PetDose& dose, std::string* why = nullptr);

// Seconds after midnight from a DICOM TM value "HHMMSS.FFFFFF" (or "HH:MM:SS" of old files).
std::optional<double> parseDicomTime(const std::string& tm);

}  // namespace mvw
