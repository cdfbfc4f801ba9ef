#pragma once
// `mvw convert` as functions: a volume (a DICOM series, NIfTI, MetaImage, or one volume of a
// study config read as every command reads the study) written as NIfTI or MetaImage with a
// JSON sidecar (OUT.json, dcm2niix's name), both files or neither.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/Frame.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/study/StudyLoader.h"  // isStudyConfig

namespace mvw::study {

struct ConversionRequest {
  std::string input;             // a volume (file or DICOM folder) or a study config (.json)
  std::filesystem::path output;  // .nii.gz, .nii or .mha
  std::string series;            // of a DICOM folder ("": its only series)
  std::string frame;             // of a 4D volume file: N or "mean" ("": every frame)
  std::string volume;            // of a study config: "" (anatomical), functional, segmentation
  bool suv = true;               // PET values in SUVbw (else Bq/ml)
};

// OUT.nii.gz -> OUT.json (dcm2niix's sidecar name); empty for an extension mvw does not write.
std::filesystem::path sidecarOf(const std::filesystem::path& output);

// Everything about the output that can be wrong is said before the input is read: a format mvw
// does not write, io::checkVolumeOutput's refusals, a sidecar name that is the input's or a
// folder's, or a sidecar an earlier `mvw convert` did not write (the name is also what a study
// config or another tool's file is called). Returns the sidecar's path; throws InputError.
std::filesystem::path checkConversionOutput(const ConversionRequest& request);

// One volume of a study config ("" or "anatomical", "functional", "segmentation": its label
// volume), read as every command reads the study: its own series choice, "frame" and PACS
// series from the verified cache, read with `pacs` (the command line's --cache and time-outs).
// Throws InputError when the study names no such volume.
Volume readStudyVolume(const std::string& studyPath, const std::string& which,
                       const io::ReadOptions& read, const pacs::Options& pacs);

// The volume to write: the input (or its study volume, its PACS series read with `pacs`), with
// --frame's choice taken. Throws InputError for a frame that is not a number or "mean".
Volume readConversionInput(const ConversionRequest& request, const pacs::Options& pacs);

// The sidecar: `description` (what `mvw info --json` says of the volume, its "path" left out)
// and where the values came from: the source, the series, the SUV factor, the frame or the
// study volume taken, and "written_by": "mvw convert".
nlohmann::json conversionSidecar(nlohmann::json description, const Volume& volume,
                                 const ConversionRequest& request);

// Both files appear or neither: written into a staging folder in the output's folder and
// moved into place together, so a failure leaves what was there before. A place that cannot be
// written is an InputError naming the output.
void writeConversion(const Volume& volume, const std::filesystem::path& output,
                     const std::filesystem::path& sidecar, const std::string& sidecarText);

// "wrote OUT (dimensions, type, unit) and OUT.json", and which volume of a study it was.
std::string conversionSummary(const Volume& volume, const ConversionRequest& request,
                              const std::filesystem::path& sidecar);

}  // namespace mvw::study
