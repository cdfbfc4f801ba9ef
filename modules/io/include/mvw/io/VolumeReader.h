#pragma once
// Reading volumes from DICOM series (directory or file), NIfTI-1/2 (.nii, .nii.gz, .hdr/.img)
// and MetaImage (.mha, .mhd). Every reader returns geometry in LPS millimetres and values in
// their physical unit. Bad input throws mvw::InputError naming the file and the problem;
// no reader allocates what a header claims before checking it against the file and the limit.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/core/Volume.h"

namespace mvw::io {

struct ReadOptions {
  // Which DICOM series, when a folder holds several: a SeriesInstanceUID, a SeriesNumber, or
  // a case-insensitive part of the SeriesDescription. Empty: the folder must hold exactly one.
  std::string series;
  // Refuse volumes larger than this many bytes in memory (default: a quarter of physical RAM).
  std::size_t maxBytes = 0;
  // Convert PET Bq/ml to SUVbw when the DICOM tags allow it.
  bool suv = true;
  // Slice distance (mm) of the regular grid that DICOM series with uneven or missing slices,
  // or gantry tilt, are resampled onto; 0: automatic (the smallest distance that occurs, not
  // below a quarter of the median, at most eight grid planes per acquired slice).
  double sliceSpacing = 0.0;
  // Compressed DICOM pixel data (JPEG, JPEG-LS, JPEG 2000, RLE) is decoded by a child process,
  // mvw-decoder, with memory and time limits: a decoder fault is the file's error, never this
  // process's (docs/design.md#isolated-decoder). false decodes in this process, and an abort
  // or a crash of vtk-dicom or GDCM is no longer turned into exit 2 (DecoderGuard.h): for the
  // fuzz harness, whose findings must happen where libFuzzer sees them.
  bool isolateDecoder = true;
};

std::size_t defaultMaxBytes();

// Why a byte count (the text `mvw info --max-memory 512M` becomes) cannot be ReadOptions'
// maxBytes; empty where it can. 1 MiB .. 1 PiB; beyond 2^64 the text is no longer a number.
std::string maxBytesProblem(const std::string& bytes);

enum class FileFormat { Dicom, Nifti, MetaImage, Unknown };
FileFormat detectFormat(const std::filesystem::path& path);

// The one volume at `path` (a DICOM series is chosen with options.series).
Volume readVolume(const std::filesystem::path& path, const ReadOptions& options = {});

// Every volume at `path`: each image series of a DICOM folder, or the one volume of a file.
std::vector<Volume> readAllVolumes(const std::filesystem::path& path,
                                   const ReadOptions& options = {});

}  // namespace mvw::io
