#include "DicomStacks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDICOMSliceSorter.h>
#include <vtkDICOMValue.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

#include <glm/geometric.hpp>

#include "DicomGeometry.h"
#include "FileChecks.h"
#include "FrameHeaders.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/PixelData.h"

namespace mvw::io::detail {

namespace {

namespace fs = std::filesystem;

bool isUncompressed(const std::string& ts) {
  // Implicit VR LE, explicit VR LE, explicit VR BE; empty: no meta header (implicit VR LE).
  return ts.empty() || ts == "1.2.840.10008.1.2" || ts == "1.2.840.10008.1.2.1" ||
         ts == "1.2.840.10008.1.2.2";
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

}  // namespace

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
    if (!isUncompressed(ts)) {
      checkEncapsulatedFrames(file, frameCodecOf(ts), {rows, cols, spp, bits}, frames);
      continue;
    }
    const std::uint64_t need = nativePixelDataBytes(
        static_cast<std::uint64_t>(rows), static_cast<std::uint64_t>(cols),
        static_cast<std::uint64_t>(frames), static_cast<std::uint64_t>(spp),
        static_cast<std::uint64_t>(bits),
        meta->Get(static_cast<int>(f), DC::PhotometricInterpretation).AsString());
    const std::uintmax_t have = regularFileSize(file);
    if (need > have)
      throw InputError(file, "truncated: the header describes " + std::to_string(need) +
                                 " bytes of pixel data but the file has only " +
                                 std::to_string(have) + " bytes");
  }
}

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
  std::string note = std::to_string(left) + " of " + countOf(n, "file") +
                     " of the series left out as not slices of its stack:";
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
         countOf(stackSlices[best], "slice") + " from " + std::to_string(stackFiles[best].size()) +
         " of " + countOf(files->GetNumberOfValues(), "file") + ", was read" +
         (left.empty() ? std::string() : "; files left out: " + listed(left));
}

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

}  // namespace mvw::io::detail
