// DICOM series through vtk-dicom: vtkDICOMDirectory groups the files of a folder (or one file)
// into series, vtkDICOMReader sorts the slices along the slice normal, decodes (GDCM for
// compressed transfer syntaxes), applies the rescale to physical units and gives the
// patient matrix (LPS). Before any pixel is read, each file's pixel-data size is checked
// against the file and the whole volume against the memory limit.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMDirectory.h>
#include <vtkDICOMItem.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDICOMSliceSorter.h>
#include <vtkDICOMTagPath.h>
#include <vtkDICOMValue.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <glm/geometric.hpp>

#include "DecoderGuard.h"
#include "DeflatedDicom.h"
#include "DicomFile.h"
#include "FileChecks.h"
#include "Formats.h"
#include "SiemensMosaic.h"
#include "SliceGeometry.h"
#include "VtkBridge.h"
#include "VtkMessages.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/Suv.h"
#include "mvw/io/DicomSeg.h"

namespace mvw::io::detail {

namespace {

namespace fs = std::filesystem;

struct SeriesRef {
  int index = 0;
  std::string uid, description, modality;
  int number = -1;
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string describe(const SeriesRef& s) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  std::string out = "#";
  out += std::to_string(s.number);
  out += " " + s.modality + " \"" + s.description + "\" (" + s.uid + ")";
  return out;
}

bool matches(const SeriesRef& s, const std::string& want) {
  if (want == s.uid) return true;
  if (!want.empty() && std::all_of(want.begin(), want.end(), ::isdigit) &&
      std::stoll(want) == s.number)
    return true;
  return !want.empty() && lower(s.description).find(lower(want)) != std::string::npos;
}

bool isUncompressed(const std::string& ts) {
  // Implicit VR LE, explicit VR LE, explicit VR BE; empty: no meta header (implicit VR LE).
  return ts.empty() || ts == "1.2.840.10008.1.2" || ts == "1.2.840.10008.1.2.1" ||
         ts == "1.2.840.10008.1.2.2";
}

// Refuses files whose header claims more pixel data than the file holds (uncompressed only:
// a compressed stream's length says nothing about the decoded size).
void checkPixelDataSizes(vtkDICOMMetaData* meta, vtkStringArray* files) {
  for (vtkIdType f = 0; f < files->GetNumberOfValues(); ++f) {
    const fs::path file(files->GetValue(f).c_str());
    const long long rows = meta->Get(static_cast<int>(f), DC::Rows).AsInt64();
    const long long cols = meta->Get(static_cast<int>(f), DC::Columns).AsInt64();
    const long long bits = meta->Get(static_cast<int>(f), DC::BitsAllocated).AsInt64();
    long long spp = meta->Get(static_cast<int>(f), DC::SamplesPerPixel).AsInt64();
    long long frames = meta->Get(static_cast<int>(f), DC::NumberOfFrames).AsInt64();
    if (spp <= 0) spp = 1;
    if (frames <= 0) frames = 1;
    if (rows <= 0 || cols <= 0) throw InputError(file, "Rows or Columns missing or not positive");
    if (bits != 1 && bits != 8 && bits != 16 && bits != 32 && bits != 64)
      throw InputError(file, "unsupported BitsAllocated " + std::to_string(bits));
    if (spp > 4) throw InputError(file, "unsupported SamplesPerPixel " + std::to_string(spp));
    if (frames > (1 << 20))
      throw InputError(file, "implausible NumberOfFrames " + std::to_string(frames));
    const std::string ts = meta->Get(static_cast<int>(f), DC::TransferSyntaxUID).AsString();
    if (!isUncompressed(ts)) continue;
    // YBR_FULL_422 stores two samples per pixel on average, not three.
    if (meta->Get(static_cast<int>(f), DC::PhotometricInterpretation).AsString() == "YBR_FULL_422")
      spp = 2;
    // Each factor is bounded above (rows, columns < 2^32, spp <= 4, frames <= 2^20, bits <= 64).
    const double need = std::ceil(static_cast<double>(rows) * cols * spp * frames * bits / 8.0);
    const std::uintmax_t have = regularFileSize(file);
    if (need > static_cast<double>(have))
      throw InputError(file, "truncated: the header describes " +
                                 std::to_string(static_cast<unsigned long long>(need)) +
                                 " bytes of pixel data but the file has only " +
                                 std::to_string(have) + " bytes");
  }
}

void fillUnitAndSuv(Volume& volume, vtkDICOMMetaData* meta, const ReadOptions& options) {
  auto& md = volume.metadata();
  const std::string rescaleType = meta->Get(0, DC::RescaleType).AsString();
  if (md.modality == "CT") {
    md.unit = rescaleType.empty() ? "HU" : rescaleType;
    return;
  }
  if (md.modality == "RTDOSE") {
    const double scaling = meta->Get(0, DC::DoseGridScaling).AsDouble();
    const std::string units = meta->Get(0, DC::DoseUnits).AsString();
    md.unit = units == "GY" ? "Gy" : units == "RELATIVE" ? "%" : units;
    if (scaling > 0 && std::isfinite(scaling) && scaling != 1.0) {
      VolumeMetadata keep = md;
      volume = volume.converted(ScalarType::Float32, scaling, 0.0);
      volume.metadata() = keep;
      volume.metadata().notes.push_back("DoseGridScaling " +
                                        meta->Get(0, DC::DoseGridScaling).AsString() + " applied");
    }
    return;
  }
  if (md.modality != "PT") {
    md.unit = rescaleType == "US" ? "" : rescaleType;
    return;
  }
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

// A DS value of `count` numbers, each a whole decimal string and at most `limit` in size
// ("nan", "1e999" and text are not: vtk-dicom would read them as 0 or inf; a position beyond
// 1 km is no place in a scanner).
bool numbersOk(const vtkDICOMValue& value, unsigned int count, double limit = 1e6) {
  if (value.GetNumberOfValues() != count) return false;
  for (unsigned int i = 0; i < count; ++i) {
    const std::string text = value.GetString(i);
    const char* begin = text.c_str();
    char* end = nullptr;
    const double x = std::strtod(begin, &end);
    if (end == begin || !(std::abs(x) <= limit)) return false;
    while (*end == ' ') ++end;
    if (*end != '\0') return false;
  }
  return true;
}

std::string fileName(vtkStringArray* files, int index) {
  return fs::path(files->GetValue(index).c_str()).filename().string();
}

// The first five names, then "..." and how many there are.
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size() && i < 5; ++i) text += (i ? ", " : "") + names[i];
  if (names.size() > 5) text += ", ... (" + std::to_string(names.size()) + " files)";
  return text;
}

// The row and column directions of an ImageOrientationPatient of six numbers, as stored (not
// normalised); nullopt when it is not six numbers.
std::optional<std::pair<glm::dvec3, glm::dvec3>> orientationAxes(const vtkDICOMValue& iop) {
  if (!numbersOk(iop, 6)) return std::nullopt;
  glm::dvec3 row, column;
  for (unsigned int a = 0; a < 3; ++a) {
    row[static_cast<int>(a)] = iop.GetDouble(a);
    column[static_cast<int>(a)] = iop.GetDouble(a + 3);
  }
  return std::pair{row, column};
}

// Every slice the reader will stack: a position of three numbers when any slice has one, and
// one orientation. Slices of different orientations (a three-plane localizer, a reformat
// filed under the acquisition's series) are not one volume; a position that is not numbers
// would be read as 0 and place its slice at the origin.
void checkSliceGeometry(vtkDICOMReader* reader, vtkStringArray* files, const fs::path& path) {
  vtkIntArray* fileIndex = reader->GetFileIndexArray();
  vtkIntArray* frameIndex = reader->GetFrameIndexArray();
  vtkDICOMMetaData* meta = reader->GetMetaData();
  if (!fileIndex || !frameIndex) return;
  const vtkIdType n = fileIndex->GetNumberOfTuples();
  bool anyPosition = false;
  for (vtkIdType s = 0; s < n && !anyPosition; ++s)
    anyPosition = meta->Get(fileIndex->GetComponent(s, 0), frameIndex->GetComponent(s, 0),
                            DC::ImagePositionPatient)
                      .IsValid();
  std::optional<glm::dvec3> firstNormal;
  int firstFile = 0;
  for (vtkIdType s = 0; s < n; ++s) {
    const int f = static_cast<int>(fileIndex->GetComponent(s, 0));
    const int frame = static_cast<int>(frameIndex->GetComponent(s, 0));
    const vtkDICOMValue& ipp = meta->Get(f, frame, DC::ImagePositionPatient);
    if (anyPosition && !numbersOk(ipp, 3))
      throw InputError(path, fileName(files, f) +
                                 (ipp.IsValid() ? ": ImagePositionPatient '" + ipp.AsString() +
                                                      "' is not three numbers"
                                                : ": no ImagePositionPatient") +
                                 ", where the other slices of the series have one: its place in "
                                 "the volume is unknown");
    const vtkDICOMValue& iop = meta->Get(f, frame, DC::ImageOrientationPatient);
    const auto axes = orientationAxes(iop);
    if (!axes) continue;  // said once for the series (below, in readSeries)
    const glm::dvec3 normal = glm::cross(axes->first, axes->second);
    if (!(glm::length(normal) > 0.5)) continue;
    if (!firstNormal) {
      firstNormal = glm::normalize(normal);
      firstFile = f;
    } else if (glm::dot(glm::normalize(normal), *firstNormal) <
               std::cos(2.0 * std::numbers::pi / 180.0)) {  // twice the grouping's 1 degree
      throw InputError(path, "its slices lie in different orientations (" +
                                 fileName(files, firstFile) + " and " + fileName(files, f) +
                                 ": ImageOrientationPatient '" +
                                 meta->Get(firstFile, 0, DC::ImageOrientationPatient).AsString() +
                                 "' and '" + iop.AsString() +
                                 "'): not one volume (a localizer or a reformat?); give a "
                                 "folder or series of one orientation");
    }
  }
}

// The files of a series (one frame each) that are not slices of its main stack: those of
// another orientation than the most common one (a localizer or a reformat filed under the
// acquisition's series), and, where others have a position, those without a usable one (a
// position of text or NaN would be read as 0, its slice put at the origin). They are left out
// before vtk-dicom sorts, so its stacks are not split at them; the gap a left-out slice leaves
// is found and filled like any missing slice. Returns the note ("" when all are kept).
std::string leaveOutStrayFiles(vtkDICOMReader* reader, vtkStringArray* files,
                               vtkSmartPointer<vtkStringArray>& kept) {
  vtkDICOMMetaData* meta = reader->GetMetaData();
  const int n = static_cast<int>(files->GetNumberOfValues());
  if (n < 2 || meta->GetNumberOfInstances() != n) return "";
  for (int f = 0; f < n; ++f)
    if (meta->Get(f, DC::NumberOfFrames).AsInt() > 1) return "";
  // Orientation groups: row and column directions within 1 degree of the group's first file.
  const double cosTolerance = std::cos(1.0 * std::numbers::pi / 180.0);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> groupAxes;
  std::vector<int> group(static_cast<std::size_t>(n), -1), groupSize;
  std::vector<bool> positioned(static_cast<std::size_t>(n), false);
  int anyPositioned = 0, oriented = 0, parallel = -1;
  for (int f = 0; f < n; ++f) {
    positioned[static_cast<std::size_t>(f)] = numbersOk(meta->Get(f, DC::ImagePositionPatient), 3);
    anyPositioned += positioned[static_cast<std::size_t>(f)];
    const auto axes = orientationAxes(meta->Get(f, DC::ImageOrientationPatient));
    if (!axes) continue;
    auto [row, column] = *axes;
    if (!(glm::length(row) > 0.5 && glm::length(column) > 0.5)) continue;
    // Two directions along one line give no slice normal: such a file has no usable
    // orientation (vtk-dicom would read every slice at one position).
    if (!(glm::length(glm::cross(glm::normalize(row), glm::normalize(column))) > 0.5)) {
      if (parallel < 0) parallel = f;
      continue;
    }
    ++oriented;
    row = glm::normalize(row);
    column = glm::normalize(column);
    int g = 0;
    while (g < static_cast<int>(groupAxes.size()) &&
           !(glm::dot(row, groupAxes[static_cast<std::size_t>(g)].first) > cosTolerance &&
             glm::dot(column, groupAxes[static_cast<std::size_t>(g)].second) > cosTolerance))
      ++g;
    if (g == static_cast<int>(groupAxes.size())) {
      groupAxes.emplace_back(row, column);
      groupSize.push_back(0);
    }
    group[static_cast<std::size_t>(f)] = g;
    ++groupSize[static_cast<std::size_t>(g)];
  }
  // In-plane pixel size: the most common among the files of usable PixelSpacing.
  std::vector<std::pair<glm::dvec2, int>> spacings;
  std::vector<int> spacingOf(static_cast<std::size_t>(n), -1);
  for (int f = 0; f < n; ++f) {
    const vtkDICOMValue& ps = meta->Get(f, DC::PixelSpacing);
    if (!numbersOk(ps, 2) || !(ps.GetDouble(0) > 0.0 && ps.GetDouble(1) > 0.0)) continue;
    const glm::dvec2 s(ps.GetDouble(0), ps.GetDouble(1));
    std::size_t k = 0;
    while (k < spacings.size() && glm::length(spacings[k].first - s) > 1e-3 * glm::length(s)) ++k;
    if (k == spacings.size()) spacings.emplace_back(s, 0);
    ++spacings[k].second;
    spacingOf[static_cast<std::size_t>(f)] = static_cast<int>(k);
  }
  const int mainSpacing = spacings.empty()
                              ? -1
                              : static_cast<int>(std::max_element(spacings.begin(), spacings.end(),
                                                                  [](const auto& a, const auto& b) {
                                                                    return a.second < b.second;
                                                                  }) -
                                                 spacings.begin());
  if (groupSize.empty() && parallel >= 0)
    throw InputError(fs::path(files->GetValue(parallel).c_str()),
                     "ImageOrientationPatient '" +
                         meta->Get(parallel, DC::ImageOrientationPatient).AsString() +
                         "' gives no slice normal (its row and column directions are "
                         "parallel): the slices cannot be stacked");
  // A file lacking what the others have (orientation, position, pixel size) is stray only
  // when the files that have it are the majority: ten files without a position beside two
  // with one are not left out.
  int spaced = 0;
  for (int k : spacingOf) spaced += k >= 0;
  const bool needOrientation = 2 * oriented > n, needPosition = 2 * anyPositioned > n,
             needSpacing = 2 * spaced > n;
  const int main = groupSize.empty()
                       ? -1
                       : static_cast<int>(std::max_element(groupSize.begin(), groupSize.end()) -
                                          groupSize.begin());
  std::vector<std::string> otherOrientation, noPosition, otherSpacing;
  int left = 0;
  kept = vtkSmartPointer<vtkStringArray>::New();
  for (int f = 0; f < n; ++f) {
    const std::size_t i = static_cast<std::size_t>(f);
    // Where the others have an orientation, one without a usable one is stray too.
    const bool strayOrientation = main >= 0 && (group[i] >= 0 ? group[i] != main : needOrientation);
    const bool strayPosition = needPosition && !positioned[i];
    const bool straySpacing =
        mainSpacing >= 0 && (spacingOf[i] >= 0 ? spacingOf[i] != mainSpacing : needSpacing);
    if (!strayOrientation && !strayPosition && !straySpacing) {
      kept->InsertNextValue(files->GetValue(f));
      continue;
    }
    ++left;
    (strayOrientation ? otherOrientation
     : strayPosition  ? noPosition
                      : otherSpacing)
        .push_back(fileName(files, f));
  }
  if (left == 0 || kept->GetNumberOfValues() < 1) return "";
  std::string note = std::to_string(left) + " of " + std::to_string(n) +
                     " files of the series left out as not slices of its stack:";
  std::string sep;
  auto reason = [&](const std::vector<std::string>& names, const std::string& why) {
    if (names.empty()) return;
    note += sep + " " + why + " (" + listed(names) + ")";
    sep = ";";
  };
  reason(otherOrientation, "another orientation, or none");
  reason(noPosition, "no usable ImagePositionPatient");
  if (mainSpacing >= 0)
    reason(otherSpacing,
           "another PixelSpacing than the " + shortNumber(spacings[mainSpacing].first.x) + " x " +
               shortNumber(spacings[mainSpacing].first.y) + " mm of the others, or none");
  return note;
}

// vtk-dicom splits a series into stacks when its files do not line up (a file of another
// orientation, one without a position, a second location per slice) and reads the first
// stack, which can be a handful of an acquisition's slices. The largest stack is read instead
// (the first of equals), and the note says which files were left out.
std::string chooseLargestStack(vtkDICOMReader* reader, vtkStringArray* files) {
  vtkStringArray* ids = reader->GetStackIDs();
  if (!ids || ids->GetNumberOfValues() < 2) return "";
  vtkNew<vtkDICOMSliceSorter> sorter;
  sorter->SetMetaData(reader->GetMetaData());
  sorter->TimeAsVectorOn();
  // Ranked by slices (an enhanced multi-frame file holds several stacks in one file).
  std::vector<std::vector<int>> stackFiles;
  std::vector<vtkIdType> stackSlices;
  std::size_t best = 0;
  for (vtkIdType s = 0; s < ids->GetNumberOfValues(); ++s) {
    sorter->SetDesiredStackID(ids->GetValue(s).c_str());
    sorter->Update();
    std::vector<int> in;
    vtkIdType slices = 0;
    if (vtkIntArray* fi = sorter->GetFileIndexArray()) {
      slices = fi->GetNumberOfTuples();
      for (vtkIdType t = 0; t < slices; ++t) in.push_back(static_cast<int>(fi->GetComponent(t, 0)));
    }
    std::sort(in.begin(), in.end());
    in.erase(std::unique(in.begin(), in.end()), in.end());
    stackFiles.push_back(std::move(in));
    stackSlices.push_back(slices);
    if (stackSlices.back() > stackSlices[best]) best = stackSlices.size() - 1;
  }
  reader->SetDesiredStackID(ids->GetValue(static_cast<vtkIdType>(best)).c_str());
  reader->UpdateInformation();
  std::vector<bool> read(static_cast<std::size_t>(files->GetNumberOfValues()), false);
  for (int f : stackFiles[best])
    if (f >= 0 && f < static_cast<int>(read.size())) read[static_cast<std::size_t>(f)] = true;
  std::vector<std::string> left;
  for (std::size_t f = 0; f < read.size(); ++f)
    if (!read[f]) left.push_back(fileName(files, static_cast<int>(f)));
  return "the series holds " + std::to_string(stackFiles.size()) +
         " stacks of slices that do not line up (orientation, position or a second location "
         "per slice): the largest, " +
         std::to_string(stackSlices[best]) + " slices from " +
         std::to_string(stackFiles[best].size()) + " of " +
         std::to_string(files->GetNumberOfValues()) + " files, was read" +
         (left.empty() ? std::string() : "; files left out: " + listed(left));
}

// Each output slice's ImagePositionPatient (vtk-dicom maps output slice -> file and frame);
// empty when any is missing.
std::vector<glm::dvec3> slicePositions(vtkDICOMReader* reader) {
  vtkIntArray* fileIndex = reader->GetFileIndexArray();
  vtkIntArray* frameIndex = reader->GetFrameIndexArray();
  vtkDICOMMetaData* meta = reader->GetMetaData();
  std::vector<glm::dvec3> positions;
  if (!fileIndex || !frameIndex || fileIndex->GetNumberOfTuples() < 2) return positions;
  for (vtkIdType s = 0; s < fileIndex->GetNumberOfTuples(); ++s) {
    const vtkDICOMValue& ipp = meta->Get(fileIndex->GetComponent(s, 0),
                                         frameIndex->GetComponent(s, 0), DC::ImagePositionPatient);
    if (ipp.GetNumberOfValues() != 3) return {};
    const glm::dvec3 p(ipp.GetDouble(0), ipp.GetDouble(1), ipp.GetDouble(2));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return {};
    positions.push_back(p);
  }
  return positions;
}

// Slices without any ImagePositionPatient: stacked in vtk-dicom's order (instance numbers),
// as far apart as SpacingBetweenSlices, else SliceThickness, else 1 mm, with a note; where
// the volume lies in the patient is unknown.
Volume spaceUnplacedSlices(Volume volume, vtkDICOMMetaData* meta) {
  double step = meta->Get(0, DC::SpacingBetweenSlices).AsDouble();
  std::string from = "SpacingBetweenSlices";
  if (!(step > 0.0 && step < 1e3)) {
    step = meta->Get(0, DC::SliceThickness).AsDouble();
    from = "SliceThickness";
  }
  if (!(step > 0.0 && step < 1e3)) {
    step = 1.0;
    from = "neither SpacingBetweenSlices nor SliceThickness says otherwise";
  }
  glm::dmat4 m = volume.worldFromIndex();
  const glm::dvec3 axis(m[2]);
  if (glm::length(axis) > 0.0) m[2] = glm::dvec4(glm::normalize(axis) * step, 0.0);
  volume.setWorldFromIndex(m);
  volume.metadata().notes.push_back(
      "no slice has an ImagePositionPatient: slices stacked in instance order " +
      shortNumber(step) + " mm apart (" + from +
      "); where the volume lies in the patient is unknown");
  return volume;
}

// The RescaleSlope of one file's frame (1 where it is missing, zero or not finite: such a
// slope is not applied, and readSeries says so) and its RescaleIntercept as stored.
std::pair<double, double> rescaleOf(vtkDICOMMetaData* meta, int file, int frame) {
  const vtkDICOMValue& s = meta->Get(file, frame, DC::RescaleSlope);
  double slope = s.IsValid() ? s.AsDouble() : 1.0;
  if (!std::isfinite(slope) || slope == 0.0) slope = 1.0;
  return {slope, meta->Get(file, frame, DC::RescaleIntercept).AsDouble()};
}

// vtk-dicom keeps an integer output type when the slope and intercept are whole numbers, and
// clips what does not fit: a RescaleSlope of 1e6 on 12-bit data read as -32768 .. 32767
// without a word. True when a slice's slope (other than 1) could take its stored values (by
// BitsStored and PixelRepresentation) beyond the integer type vtk-dicom announces; the series
// is then read as stored and rescaled here, to float32 (rescaleSlices).
bool rescaleMayClip(vtkDICOMMetaData* meta, vtkIntArray* fileIndex, vtkIntArray* frameIndex,
                    int vtkType) {
  if (vtkType == VTK_FLOAT || vtkType == VTK_DOUBLE || !fileIndex || !frameIndex) return false;
  const double lo = vtkDataArray::GetDataTypeMin(vtkType),
               hi = vtkDataArray::GetDataTypeMax(vtkType);
  for (vtkIdType t = 0; t < fileIndex->GetNumberOfTuples(); ++t)
    for (int c = 0; c < fileIndex->GetNumberOfComponents(); ++c) {
      const int f = fileIndex->GetComponent(t, c), frame = frameIndex->GetComponent(t, c);
      const auto [slope, intercept] = rescaleOf(meta, f, frame);
      if (slope == 1.0) continue;
      int bits = meta->Get(f, DC::BitsStored).AsInt();
      if (bits < 1 || bits > 32) bits = meta->Get(f, DC::BitsAllocated).AsInt();
      if (bits < 1 || bits > 32) continue;
      const bool isSigned = meta->Get(f, DC::PixelRepresentation).AsInt() == 1;
      const double storedMin = isSigned ? -std::ldexp(1.0, bits - 1) : 0.0;
      const double storedMax =
          isSigned ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
      const double a = slope * storedMin + intercept, b = slope * storedMax + intercept;
      if (std::min(a, b) < lo - 0.5 || std::max(a, b) > hi + 0.5) return true;
    }
  return false;
}

// The stored values of `volume` (read with AutoRescaleOff) times each slice's own slope plus
// its intercept, as float32. Slice k, component c comes from the file and frame the reader's
// index arrays name for slice k and time point c / samplesPerPixel.
Volume rescaleSlices(const Volume& volume, vtkDICOMMetaData* meta, vtkIntArray* fileIndex,
                     vtkIntArray* frameIndex, int samplesPerPixel) {
  const glm::ivec3 d = volume.dimensions();
  const int comps = volume.components();
  Volume out(d, comps, ScalarType::Float32, volume.worldFromIndex());
  out.metadata() = volume.metadata();
  const std::size_t plane = static_cast<std::size_t>(d.x) * d.y;
  float* dst = out.dataAs<float>();
  dispatchScalar(volume.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* src = volume.dataAs<T>();
    for (int k = 0; k < d.z; ++k)
      for (int c = 0; c < comps; ++c) {
        const int time =
            std::min(c / std::max(samplesPerPixel, 1), fileIndex->GetNumberOfComponents() - 1);
        const int f = fileIndex->GetComponent(k, time), frame = frameIndex->GetComponent(k, time);
        auto [slope, intercept] = rescaleOf(meta, f, frame);
        if (!std::isfinite(intercept)) intercept = 0.0;
        const std::size_t base = static_cast<std::size_t>(k) * plane * comps + c;
        for (std::size_t p = 0; p < plane; ++p)
          dst[base + p * comps] =
              static_cast<float>(static_cast<double>(src[base + p * comps]) * slope + intercept);
      }
    return 0;
  });
  return out;
}

bool isMosaic(vtkDICOMMetaData* meta) {
  const vtkDICOMValue& type = meta->Get(0, DC::ImageType);
  for (unsigned int i = 0; i < type.GetNumberOfValues(); ++i)
    if (type.GetString(i) == "MOSAIC") return true;
  return false;
}

Volume unpackMosaicFrom(Volume volume, vtkDICOMMetaData* meta) {
  const vtkDICOMTag tag =
      meta->ResolvePrivateTag(0, vtkDICOMTag(0x0029, 0x1010), "SIEMENS CSA HEADER");
  const vtkDICOMValue& csa = meta->Get(0, tag);
  const unsigned char* bytes = csa.IsValid() ? csa.GetUnsignedCharData() : nullptr;
  const std::size_t size = bytes ? csa.GetNumberOfValues() : 0;
  return unpackMosaic(std::move(volume), bytes, size,
                      meta->Get(0, DC::SpacingBetweenSlices).AsDouble(),
                      meta->Get(0, DC::SliceThickness).AsDouble());
}

// vtk-dicom returns the frames of a multi-frame file that carries no per-frame position
// (RT dose grids with GridFrameOffsetVector, secondary captures) as vector components of a
// single slice. Frames are slices: stack them along the slice normal.
Volume stackFramesAsSlices(const Volume& in, int frames, int spp, vtkDICOMMetaData* meta) {
  const glm::ivec3 d = in.dimensions();
  Volume out({d.x, d.y, frames}, spp, in.scalarType(), in.worldFromIndex());
  out.metadata() = in.metadata();
  const std::size_t value = scalarSize(in.scalarType());
  const std::size_t pixelBytes = static_cast<std::size_t>(spp) * value;
  for (int f = 0; f < frames; ++f)
    for (std::size_t p = 0; p < static_cast<std::size_t>(d.x) * d.y; ++p)
      std::memcpy(out.data() + (static_cast<std::size_t>(f) * d.x * d.y + p) * pixelBytes,
                  in.data() + (p * frames + f) * pixelBytes, pixelBytes);
  const glm::dmat4& w = in.worldFromIndex();
  const glm::dvec3 normal = glm::normalize(glm::cross(glm::dvec3(w[0]), glm::dvec3(w[1])));
  const vtkDICOMValue& offsets = meta->Get(0, DC::GridFrameOffsetVector);
  glm::dmat4 m = w;
  if (offsets.GetNumberOfValues() == static_cast<std::size_t>(frames) && frames > 1) {
    const double step = offsets.GetDouble(1) - offsets.GetDouble(0);
    bool uniform = step != 0.0;
    for (int f = 2; f < frames; ++f)
      uniform &= std::abs(offsets.GetDouble(f) - offsets.GetDouble(f - 1) - step) <
                 1e-3 * std::abs(step) + 1e-4;
    m[2] = glm::dvec4(normal * step, 0.0);
    m[3] = w[3] + glm::dvec4(normal * offsets.GetDouble(0), 0.0);
    out.metadata().notes.push_back(
        std::string("frames stacked along the slice normal by GridFrameOffsetVector") +
        (uniform ? "" : " (NOT uniform: the volume uses the first step)"));
  } else {
    m[2] = glm::dvec4(normal, 0.0);
    out.metadata().notes.push_back("frames without positions stacked as slices 1 mm apart");
  }
  out.setWorldFromIndex(m);
  return out;
}

Volume readSeries(const fs::path& path, vtkStringArray* files, const SeriesRef& ref,
                  const ReadOptions& options) {
  fs::path first(files->GetValue(0).c_str());
  DecoderGuard guard(path);
  VtkMessageScope messages;
  vtkNew<vtkDICOMReader> reader;
  reader->SetFileNames(files);
  reader->SetMemoryRowOrderToFileNative();  // voxel (0,0) is the first pixel of the file
  reader->TimeAsVectorOn();                 // time frames become components, as for NIfTI
  reader->AutoRescaleOn();
  reader->UpdateInformation();
  if (!messages.firstError().empty())
    throw InputError(first, "cannot read the DICOM header: " + messages.firstError());
  checkPixelDataSizes(reader->GetMetaData(), files);
  vtkSmartPointer<vtkStringArray> kept;
  const std::string strayNote = leaveOutStrayFiles(reader, files, kept);
  if (!strayNote.empty()) {
    files = kept;
    first = fs::path(files->GetValue(0).c_str());
    reader->SetFileNames(files);
    reader->UpdateInformation();
    if (!messages.firstError().empty())
      throw InputError(first, "cannot read the DICOM header: " + messages.firstError());
  }
  const std::string stackNote = chooseLargestStack(reader, files);
  checkSliceGeometry(reader, files, path);

  vtkInformation* info = reader->GetOutputInformation(0);
  int extent[6];
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  const glm::ivec3 dims{extent[1] - extent[0] + 1, extent[3] - extent[2] + 1,
                        extent[5] - extent[4] + 1};
  const int components = std::max(1, vtkImageData::GetNumberOfScalarComponents(info));
  const int vtkType = vtkImageData::GetScalarType(info);
  const bool rescaleHere = rescaleMayClip(reader->GetMetaData(), reader->GetFileIndexArray(),
                                          reader->GetFrameIndexArray(), vtkType);
  const int typeSize = rescaleHere ? 4 : vtkDataArray::GetDataTypeSize(vtkType);
  checkedVolumeBytes(first, dims, components, static_cast<std::size_t>(std::max(typeSize, 1)),
                     options.maxBytes);

  if (rescaleHere) reader->AutoRescaleOff();  // the stored values; rescaled below, to float32
  reader->Update();
  if (!messages.firstError().empty() || reader->GetErrorCode() != 0) {
    std::string why = messages.firstError();
    if (why.empty()) why = "error code " + std::to_string(reader->GetErrorCode());
    throw InputError(first, "cannot read the DICOM pixel data: " + why);
  }
  vtkImageData* image = reader->GetOutput();
  Volume volume = volumeFromImage(image, first);
  if (rescaleHere)
    volume = rescaleSlices(volume, reader->GetMetaData(), reader->GetFileIndexArray(),
                           reader->GetFrameIndexArray(),
                           std::max(1, reader->GetMetaData()->Get(0, DC::SamplesPerPixel).AsInt()));
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  glm::dmat4 patientFromData(1.0);
  if (vtkMatrix4x4* p = reader->GetPatientMatrix()) {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) patientFromData[c][r] = p->GetElement(r, c);
  }
  glm::dmat4 dataFromIndex(1.0);
  for (int a = 0; a < 3; ++a) {
    dataFromIndex[a][a] = spacing[a] > 0 ? spacing[a] : 1.0;
    dataFromIndex[3][a] = origin[a];
  }
  volume.setWorldFromIndex(patientFromData * dataFromIndex);

  vtkDICOMMetaData* meta = reader->GetMetaData();
  const int spp = std::max(1, meta->Get(0, DC::SamplesPerPixel).AsInt());
  const int frames = meta->Get(0, DC::NumberOfFrames).AsInt();
  if (files->GetNumberOfValues() == 1 && frames > 1 && volume.dimensions().z == 1 &&
      volume.components() == frames * spp)
    volume = stackFramesAsSlices(volume, frames, spp, meta);
  else if (files->GetNumberOfValues() == 1 && frames <= 1 && volume.dimensions().z == 1 &&
           isMosaic(meta))
    volume = unpackMosaicFrom(std::move(volume), meta);
  else {
    const std::vector<glm::dvec3> positions = slicePositions(reader);
    if (positions.empty() && volume.dimensions().z > 1)
      volume = spaceUnplacedSlices(std::move(volume), meta);
    else
      volume =
          placeSlices(std::move(volume), positions, options.sliceSpacing, options.maxBytes, first);
  }
  auto& md = volume.metadata();
  md.format = "DICOM";
  md.sourcePath = path.string();
  md.modality = ref.modality.empty() ? meta->Get(0, DC::Modality).AsString() : ref.modality;
  md.seriesInstanceUid = ref.uid;
  md.seriesDescription = ref.description;
  md.seriesNumber = ref.number;
  md.frameOfReferenceUid = meta->Get(0, DC::FrameOfReferenceUID).AsString();
  const vtkDICOMValue& iop = meta->Get(0, 0, DC::ImageOrientationPatient);
  if (iop.GetNumberOfValues() != 6) {
    md.notes.push_back("no ImageOrientationPatient: patient orientation unknown, axes assumed LPS");
  } else {
    // Two unit directions, at right angles; anything else was replaced by the reader.
    const auto axes = orientationAxes(iop);
    const bool usable = axes && std::abs(glm::length(axes->first) - 1.0) < 0.01 &&
                        std::abs(glm::length(axes->second) - 1.0) < 0.01 &&
                        std::abs(glm::dot(axes->first, axes->second)) < 0.01;
    if (!usable)
      md.notes.push_back("ImageOrientationPatient '" + iop.AsString() +
                         "' is not two perpendicular unit directions: axes assumed LPS");
  }
  // In-plane voxel size: a missing, zero, negative or non-numeric PixelSpacing was replaced.
  const vtkDICOMValue& ps = meta->Get(0, 0, DC::PixelSpacing);
  const bool spacingUsable = ps.GetNumberOfValues() == 2 && ps.GetDouble(0) > 0 &&
                             ps.GetDouble(1) > 0 && std::isfinite(ps.GetDouble(0)) &&
                             std::isfinite(ps.GetDouble(1));
  if (!spacingUsable) {
    char size[64];
    std::snprintf(size, sizeof size, "%g x %g mm", volume.spacing().x, volume.spacing().y);
    md.notes.push_back(
        (ps.IsValid() ? "PixelSpacing '" + ps.AsString() + "' is not usable" : "no PixelSpacing") +
        ": in-plane voxel size " + size + " assumed");
  }
  const vtkDICOMValue& slope = meta->Get(0, 0, DC::RescaleSlope);
  if (rescaleHere)
    md.notes.push_back(
        "RescaleSlope and RescaleIntercept applied here, to float32: on the "
        "stored values' range they could leave the reader's integer type");
  if (slope.IsValid() && !(std::isfinite(slope.GetDouble(0)) && slope.GetDouble(0) != 0.0))
    md.notes.push_back("RescaleSlope '" + slope.AsString() +
                       "' is not a usable factor: the stored values were not rescaled by it");
  if (!strayNote.empty()) md.notes.insert(md.notes.begin(), strayNote);
  if (!stackNote.empty()) md.notes.push_back(stackNote);
  if (reader->GetTimeDimension() > 1)
    md.notes.push_back(std::to_string(reader->GetTimeDimension()) +
                       " time points stored as components");
  else if (volume.components() > spp && spp == 1)
    md.notes.push_back(std::to_string(volume.components()) +
                       " files share each slice position: read as " +
                       std::to_string(volume.components()) + " frames (components) per slice");
  fillUnitAndSuv(volume, meta, options);
  return volume;
}

SeriesRef seriesRefFrom(vtkDICOMMetaData* meta) {
  SeriesRef s;
  s.uid = meta->Get(DC::SeriesInstanceUID).AsString();
  s.description = meta->Get(DC::SeriesDescription).AsString();
  s.number = meta->Get(DC::SeriesNumber).IsValid() ? meta->Get(DC::SeriesNumber).AsInt() : -1;
  s.modality = meta->Get(DC::Modality).AsString();
  return s;
}

// One file: parsed directly, so files without a Part 10 meta header still load and a file
// that is not an image says what it is.
Volume readSingleFile(const fs::path& path, const ReadOptions& options) {
  regularFileSize(path);
  if (const auto inflated = inflateDeflatedDicom(path, options.maxBytes)) {
    Volume volume = readSingleFile(inflated->path(), options);
    volume.metadata().sourcePath = path.string();
    volume.metadata().notes.push_back(
        "Deflated Explicit VR Little Endian: the data set was inflated before reading");
    return volume;
  }
  DecoderGuard guard(path);
  vtkNew<vtkDICOMMetaData> meta;
  const ParsedDicomFile file = parseDicomFile(path, meta);
  if (meta->Get(DC::SOPClassUID).AsString() == "1.2.840.10008.5.1.4.1.1.66.4")  // DicomSeg.cpp
    return labelVolume(segmentationFromHeader(path, meta, file, options));
  if (!file.pixelData) {
    // A DICOMDIR (Media Storage Directory, or the name) indexes the images of a medium.
    if (meta->Get(DC::MediaStorageSOPClassUID).AsString() == "1.2.840.10008.1.3.10" ||
        path.filename() == "DICOMDIR")
      throw InputError(
          path,
          "is a DICOMDIR, the index of a DICOM medium, not an image: give its "
          "folder (" +
              (path.parent_path().empty() ? std::string(".") : path.parent_path().string()) +
              ") to read the series it lists");
    const std::string modality = meta->Get(DC::Modality).AsString();
    throw InputError(path, "no pixel data: " +
                               (modality.empty() ? std::string("this DICOM object")
                                                 : "a " + modality + " object") +
                               " is not an image volume");
  }
  if (!meta->Has(DC::Rows) || !meta->Has(DC::Columns))
    throw InputError(path, "pixel data without Rows and Columns: not a usable image");
  vtkNew<vtkStringArray> files;
  files->InsertNextValue(path.string());
  return readSeries(path, files, seriesRefFrom(meta), options);
}

}  // namespace

std::vector<Volume> readDicom(const fs::path& path, const ReadOptions& options, bool allSeries) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    std::vector<Volume> one;
    one.push_back(readSingleFile(path, options));
    return one;
  }
  DecoderGuard guard(path);
  VtkMessageScope messages;
  vtkNew<vtkDICOMDirectory> dir;
  dir->SetDirectoryName(path.c_str());
  dir->SetScanDepth(8);
  dir->RequirePixelDataOn();
  dir->Update();
  std::vector<SeriesRef> series;
  for (int i = 0; i < dir->GetNumberOfSeries(); ++i) {
    const vtkDICOMItem& rec = dir->GetSeriesRecord(i);
    SeriesRef s;
    s.index = i;
    s.uid = rec.Get(DC::SeriesInstanceUID).AsString();
    s.description = rec.Get(DC::SeriesDescription).AsString();
    s.number = rec.Get(DC::SeriesNumber).IsValid() ? rec.Get(DC::SeriesNumber).AsInt() : -1;
    vtkDICOMMetaData* meta = dir->GetMetaDataForSeries(i);
    s.modality = meta ? meta->Get(DC::Modality).AsString() : "";
    series.push_back(s);
  }
  if (series.empty()) {
    const std::string err = messages.firstError();
    throw InputError(
        path, err.empty() ? "no DICOM image series in this folder (files without pixel "
                            "data, such as RT plans, structure sets and reports, are not volumes)"
                          : "no readable DICOM image series: " + err);
  }
  std::vector<SeriesRef> chosen;
  if (!options.series.empty()) {
    for (const auto& s : series)
      if (matches(s, options.series)) chosen.push_back(s);
    if (chosen.empty()) {
      std::string list;
      for (const auto& s : series) list += "\n  " + describe(s);
      throw InputError(path, "no series matches '" + options.series + "'; the series are:" + list);
    }
  } else {
    chosen = series;
  }
  // One image series and segmentations of it (a PET beside its DICOM SEG): the one volume is
  // the image series; the SEGs are named in its metadata, for a tool to take as its labels.
  std::vector<std::string> segFiles;
  if (!allSeries && options.series.empty() && chosen.size() > 1) {
    std::vector<SeriesRef> images;
    for (const auto& s : chosen) {
      vtkStringArray* files = dir->GetFileNamesForSeries(s.index);
      if (s.modality == "SEG" && files->GetNumberOfValues() == 1)
        segFiles.push_back(files->GetValue(0));
      else
        images.push_back(s);
    }
    if (images.size() == 1) {
      chosen = images;
    } else {
      segFiles.clear();
    }
  }
  if (!allSeries && chosen.size() > 1) {
    std::string list;
    for (const auto& s : chosen) list += "\n  " + describe(s);
    throw InputError(path, std::to_string(chosen.size()) +
                               " series here; choose one by UID, number or description:" + list);
  }
  // Every series asked for; among several, one that cannot be read is said in a note of the
  // first that can (a folder is still usable when one of its series is not), and its error is
  // the folder's only when none can be read.
  std::vector<Volume> volumes;
  std::vector<std::string> unread;
  std::exception_ptr firstFailure;
  for (const auto& s : chosen) {
    vtkStringArray* files = dir->GetFileNamesForSeries(s.index);
    try {
      if (s.modality == "SEG" && files->GetNumberOfValues() == 1)  // DicomSeg.cpp
        volumes.push_back(labelVolume(readDicomSegmentation(files->GetValue(0).c_str(), options)));
      else
        volumes.push_back(readSeries(path, files, s, options));
    } catch (const InputError& e) {
      if (chosen.size() == 1) throw;
      if (!firstFailure) firstFailure = std::current_exception();
      unread.push_back("series " + describe(s) + " not read: " + e.what());
    }
  }
  if (volumes.empty() && firstFailure) std::rethrow_exception(firstFailure);
  for (const std::string& note : unread) volumes.front().metadata().notes.push_back(note);
  volumes.front().metadata().segmentationFiles = segFiles;
  return volumes;
}

}  // namespace mvw::io::detail
