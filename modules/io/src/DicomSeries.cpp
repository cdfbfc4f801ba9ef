// DICOM series through vtk-dicom: vtkDICOMDirectory groups the files of a folder (or one file)
// into series, vtkDICOMReader sorts the slices along the slice normal, decodes (GDCM for
// compressed transfer syntaxes), applies the rescale to physical units and gives the
// patient matrix (LPS). Before any pixel is read, each file's pixel-data size is checked
// against the file and the whole volume against the memory limit. This file chooses the
// series and runs the reader; the files and stacks it reads are DicomStacks', where the
// slices lie DicomGeometry's, the values' units DicomUnits' and DicomSuv's.
#include <algorithm>
#include <cctype>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include <vtkDICOMDictHash.h>
#include <vtkDICOMDirectory.h>
#include <vtkDICOMItem.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDICOMValue.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include "CheckedDicomReader.h"
#include "DecoderGuard.h"
#include "DeflatedDicom.h"
#include "DicomFile.h"
#include "DicomGeometry.h"
#include "DicomStacks.h"
#include "DicomUnits.h"
#include "FileChecks.h"
#include "Formats.h"
#include "IsolatedDecoder.h"
#include "VtkBridge.h"
#include "VtkMessages.h"
#include "mvw/core/Error.h"
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

// SeriesNumber is type 2: present but empty means no number, as absent does (-1), not 0.
int seriesNumberOf(const vtkDICOMValue& value) {
  if (!value.IsValid() || value.AsString().find_first_not_of(' ') == std::string::npos) return -1;
  return value.AsInt();
}

std::string describe(const SeriesRef& s) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  std::string out = s.number < 0 ? "(no number)" : "#";
  if (s.number >= 0) out += std::to_string(s.number);
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

// Throws what vtk-dicom said while reading the headers, naming `first`.
void checkHeaderRead(const VtkMessageScope& messages, const fs::path& first) {
  if (!messages.firstError().empty())
    throw InputError(first, "cannot read the DICOM header: " + messages.firstError());
}

// The reader's output as a volume in the patient frame, after its size is held to
// options.maxBytes. `rescaleHere` (rescaleMayClip): the stored values were read and are
// rescaled here, to float32. Compressed pixel data is decoded by a child process
// (IsolatedDecoder.h) unless options.isolateDecoder is off; `input` is what the user named.
Volume readVoxels(vtkDICOMReader* reader, const VtkMessageScope& messages, const fs::path& input,
                  const fs::path& first, const ReadOptions& options, bool& rescaleHere) {
  vtkInformation* info = reader->GetOutputInformation(0);
  const auto [dims, components, vtkType] = voxelLayout(info);
  rescaleHere = rescaleMayClip(reader->GetMetaData(), reader->GetFileIndexArray(),
                               reader->GetFrameIndexArray(), vtkType);
  const int typeSize = rescaleHere ? 4 : vtkDataArray::GetDataTypeSize(vtkType);
  checkedVolumeBytes(first, dims, components, static_cast<std::size_t>(std::max(typeSize, 1)),
                     options.maxBytes);

  if (rescaleHere) reader->AutoRescaleOff();  // the stored values; rescaled below, to float32
  Volume volume;
  glm::dmat4 worldFromIndex(1.0);
  if (options.isolateDecoder && hasCompressedPixelData(reader->GetMetaData())) {
    if (rescaleHere) reader->UpdateInformation();  // the stored values' type
    volume = decodeInChild(reader, input, first);
    double origin[3], spacing[3];
    info->Get(vtkDataObject::ORIGIN(), origin);
    info->Get(vtkDataObject::SPACING(), spacing);
    worldFromIndex = patientWorldFromIndex(reader, origin, spacing);
  } else {
    reader->Update();
    if (!messages.firstError().empty() || reader->GetErrorCode() != 0) {
      std::string why = messages.firstError();
      if (why.empty()) why = "error code " + std::to_string(reader->GetErrorCode());
      throw InputError(first, "cannot read the DICOM pixel data: " + why);
    }
    vtkImageData* image = reader->GetOutput();
    volume = volumeFromImage(image, first);
    worldFromIndex = patientWorldFromIndex(reader, image);
  }
  if (rescaleHere)
    volume = rescaleSlices(volume, reader->GetMetaData(), reader->GetFileIndexArray(),
                           reader->GetFrameIndexArray(),
                           std::max(1, reader->GetMetaData()->Get(0, DC::SamplesPerPixel).AsInt()));
  volume.setWorldFromIndex(worldFromIndex);
  return volume;
}

Volume readSeries(const fs::path& path, vtkStringArray* files, const SeriesRef& ref,
                  const ReadOptions& options) {
  fs::path first(files->GetValue(0).c_str());
  DecoderGuard guard(path, options.isolateDecoder);
  VtkMessageScope messages;
  vtkNew<CheckedDicomReader> reader;
  reader->SetFileNames(files);
  reader->SetMemoryRowOrderToFileNative();  // voxel (0,0) is the first pixel of the file
  reader->TimeAsVectorOn();                 // time frames become components, as for NIfTI
  reader->AutoRescaleOn();
  reader->UpdateInformation();
  checkHeaderRead(messages, first);
  checkPixelDataSizes(reader->GetMetaData(), files);
  vtkSmartPointer<vtkStringArray> kept;
  const std::string strayNote = leaveOutStrayFiles(reader, files, kept);
  if (!strayNote.empty()) {
    files = kept;
    first = fs::path(files->GetValue(0).c_str());
    reader->SetFileNames(files);
    reader->UpdateInformation();
    checkHeaderRead(messages, first);
  }
  const std::string stackNote = chooseLargestStack(reader, files);
  checkSliceGeometry(reader, files, path);

  bool rescaleHere = false;
  Volume volume = readVoxels(reader, messages, path, first, options, rescaleHere);
  volume =
      arrangeSlices(std::move(volume), reader, files->GetNumberOfValues() == 1, options, first);

  vtkDICOMMetaData* meta = reader->GetMetaData();
  const int spp = std::max(1, meta->Get(0, DC::SamplesPerPixel).AsInt());
  auto& md = volume.metadata();
  md.format = "DICOM";
  md.sourcePath = path.string();
  md.modality = ref.modality.empty() ? meta->Get(0, DC::Modality).AsString() : ref.modality;
  md.seriesInstanceUid = ref.uid;
  md.seriesDescription = ref.description;
  md.seriesNumber = ref.number;
  md.frameOfReferenceUid = meta->Get(0, DC::FrameOfReferenceUID).AsString();
  noteGeometryFallbacks(volume, meta);
  noteRescale(volume, meta, rescaleHere);
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
  s.number = seriesNumberOf(meta->Get(DC::SeriesNumber));
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
  DecoderGuard guard(path, options.isolateDecoder);
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
  DecoderGuard guard(path, options.isolateDecoder);
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
    s.number = seriesNumberOf(rec.Get(DC::SeriesNumber));
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
