#include "DicomSuv.h"

#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMTagPath.h>
#include <vtkDICOMValue.h>

#include "mvw/core/Suv.h"

namespace mvw::io::detail {

void fillPetUnitAndSuv(Volume& volume, vtkDICOMMetaData* meta, const ReadOptions& options) {
  auto& md = volume.metadata();
  const std::string units = meta->Get(0, DC::Units).AsString();
  if (units != "BQML") {
    md.unit = units.empty() ? "" : units;
    md.notes.push_back("PET Units is '" + units + "', not BQML: values kept as stored, no SUV");
    return;
  }
  md.unit = "Bq/ml";
  if (!options.suv) {
    md.notes.push_back("SUV conversion turned off: values in Bq/ml");
    return;
  }
  PetDose dose;
  const vtkDICOMTag seq = DC::RadiopharmaceuticalInformationSequence;
  dose.injectedDoseBq = meta->Get(0, vtkDICOMTagPath(seq, 0, DC::RadionuclideTotalDose)).AsDouble();
  dose.halfLifeSeconds = meta->Get(0, vtkDICOMTagPath(seq, 0, DC::RadionuclideHalfLife)).AsDouble();
  dose.patientWeightKg = meta->Get(0, DC::PatientWeight).AsDouble();
  // The first file's tags serve the whole series; a series whose files disagree on them (edited
  // or merged) is said to, naming two values that differ, since its SUV rests on one file's.
  for (const auto& [tag, name] :
       {std::pair{DC::PatientWeight, "PatientWeight"}, std::pair{DC::SeriesTime, "SeriesTime"}}) {
    const std::string first = meta->Get(0, tag).AsString();
    for (int f = 1; f < meta->GetNumberOfInstances(); ++f)
      if (meta->Get(f, tag).AsString() != first) {
        md.notes.push_back(std::string(name) + " differs between the files of the series ('" +
                           first + "' in the first, '" + meta->Get(f, tag).AsString() +
                           "' in file " + std::to_string(f + 1) + "): the first file's is used");
        break;
      }
  }
  dose.decayCorrection = meta->Get(0, DC::DecayCorrection).AsString();
  std::string start =
      meta->Get(0, vtkDICOMTagPath(seq, 0, DC::RadiopharmaceuticalStartTime)).AsString();
  const std::string startDateTime =
      meta->Get(0, vtkDICOMTagPath(seq, 0, DC::RadiopharmaceuticalStartDateTime)).AsString();
  if (start.empty() && startDateTime.size() > 8) start = startDateTime.substr(8);
  std::string reference = meta->Get(0, DC::SeriesTime).AsString();
  std::string referenceDate = meta->Get(0, DC::SeriesDate).AsString();
  if (reference.empty()) {
    reference = meta->Get(0, DC::AcquisitionTime).AsString();
    referenceDate = meta->Get(0, DC::AcquisitionDate).AsString();
  }
  const auto injection = parseDicomTime(start);
  const auto ref = parseDicomTime(reference);
  // With both dates the interval is exact (a next-day scan of a long-lived isotope, or a series
  // time before the injection, tell themselves apart); else times of day.
  const auto injectionDay = parseDicomDate(startDateTime);
  const auto referenceDay = parseDicomDate(referenceDate);
  std::string why;
  std::optional<double> factor;
  if (dose.decayCorrection == "START" && (!injection || !ref)) {
    why = "injection time or series time missing";
  } else {
    dose.injectionTimeSeconds = injection.value_or(0.0);
    dose.referenceTimeSeconds = ref.value_or(0.0);
    if (injectionDay && referenceDay) {
      dose.injectionTimeSeconds += *injectionDay;
      dose.referenceTimeSeconds += *referenceDay;
      dose.timesHaveDates = true;
    }
    factor = suvbwFactor(dose, &why);
  }
  if (!factor) {
    md.notes.push_back("values in Bq/ml: SUVbw not computed (" + why + ")");
    return;
  }
  VolumeMetadata keep = md;
  volume = volume.converted(ScalarType::Float32, *factor, 0.0);
  volume.metadata() = keep;
  volume.metadata().unit = "SUVbw";
  volume.metadata().suvFactor = *factor;
  char text[200];
  std::snprintf(text, sizeof text,
                "SUVbw = Bq/ml x %.6g (weight %g kg, dose %.6g Bq, decay correction %s)", *factor,
                dose.patientWeightKg, dose.injectedDoseBq, dose.decayCorrection.c_str());
  volume.metadata().notes.push_back(text);
}

}  // namespace mvw::io::detail
