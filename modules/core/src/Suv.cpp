#include "mvw/core/Suv.h"

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace mvw {

std::optional<double> suvbwFactor(const PetDose& dose, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<double> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (!(dose.injectedDoseBq > 0)) return fail("RadionuclideTotalDose missing or not positive");
  // Beyond these the tags are wrong, not the patient: an SUV from them would be off by orders
  // of magnitude and look like a finding.
  if (!(dose.injectedDoseBq <= kMaxInjectedDoseBq))
    return fail("RadionuclideTotalDose is above 100 GBq: not a diagnostic dose");
  if (!(dose.patientWeightKg > 0)) return fail("PatientWeight missing or not positive");
  if (!(dose.patientWeightKg <= kMaxPatientWeightKg))
    return fail("PatientWeight is above 1000 kg: not a patient's weight");
  double doseAtReference = dose.injectedDoseBq;
  if (dose.decayCorrection == "START") {
    if (!(dose.halfLifeSeconds > 0)) return fail("RadionuclideHalfLife missing or not positive");
    double dt = dose.referenceTimeSeconds - dose.injectionTimeSeconds;
    bool wrapped = false;
    if (!dose.timesHaveDates && dt < -kMaxEarlySeriesSeconds) {
      dt += 24.0 * 3600.0;  // the scan started after midnight, the injection before
      wrapped = true;
    }
    char text[240];
    if (dt < -kMaxEarlySeriesSeconds) {
      std::snprintf(text, sizeof text,
                    "the series starts %.1f h before the injection "
                    "(RadiopharmaceuticalStartDateTime, SeriesDate/Time): inconsistent times",
                    -dt / 3600.0);
      return fail(text);
    }
    const double halfLives = dt / dose.halfLifeSeconds;
    if (halfLives > (wrapped ? kMaxHalfLivesAfterMidnight : kMaxHalfLives)) {
      std::snprintf(text, sizeof text,
                    "the series starts %.1f h (%.1f half-lives) after the injection%s: the "
                    "injection and series times are inconsistent",
                    dt / 3600.0, halfLives,
                    wrapped ? ", reading its earlier time of day as the next day" : "");
      return fail(text);
    }
    doseAtReference = dose.injectedDoseBq * std::exp2(-dt / dose.halfLifeSeconds);
  } else if (dose.decayCorrection != "ADMIN") {
    return fail("DecayCorrection is neither START nor ADMIN");
  }
  return dose.patientWeightKg * 1000.0 / doseAtReference;
}

std::optional<double> parseDicomTime(const std::string& tm) {
  std::string digits;
  std::size_t i = 0;
  for (; i < tm.size() && tm[i] != '.'; ++i) {
    if (std::isdigit(static_cast<unsigned char>(tm[i])))
      digits += tm[i];
    else if (tm[i] != ':' && tm[i] != ' ')
      return std::nullopt;
  }
  if (digits.size() < 2 || digits.size() > 6 || digits.size() % 2) return std::nullopt;
  digits.resize(6, '0');
  const int h = std::stoi(digits.substr(0, 2)), m = std::stoi(digits.substr(2, 2)),
            s = std::stoi(digits.substr(4, 2));
  if (h > 23 || m > 59 || s > 60) return std::nullopt;
  double fraction = 0.0, scale = 0.1;
  for (++i; i < tm.size() && std::isdigit(static_cast<unsigned char>(tm[i])); ++i, scale /= 10)
    fraction += (tm[i] - '0') * scale;
  return h * 3600.0 + m * 60.0 + s + fraction;
}

std::optional<double> parseDicomDate(const std::string& da) {
  if (da.size() < 8) return std::nullopt;
  for (std::size_t i = 0; i < 8; ++i)
    if (!std::isdigit(static_cast<unsigned char>(da[i]))) return std::nullopt;
  const std::chrono::year_month_day day{std::chrono::year(std::stoi(da.substr(0, 4))),
                                        std::chrono::month(std::stoul(da.substr(4, 2))),
                                        std::chrono::day(std::stoul(da.substr(6, 2)))};
  if (!day.ok()) return std::nullopt;
  return 86400.0 * std::chrono::sys_days(day).time_since_epoch().count();
}

}  // namespace mvw
