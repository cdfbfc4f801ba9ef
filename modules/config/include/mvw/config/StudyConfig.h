#pragma once
// A study config (JSON) names the anatomical and functional volumes of a paired study.
// Plain structs with defaults, validated completely on load: an unknown key, a wrong type or
// a missing file is an InputError naming the config file and the key, before any heavy work.
//
//   { "name": "Cranium CT",
//     "anatomical": { "path": "../data/cranium/dicom", "series": "" },
//     "functional": { "path": "../data/pet.nii.gz", "kind": "pet" } }
//
// Relative paths are relative to the config file's folder.
#include <filesystem>
#include <optional>
#include <string>

namespace mvw::config {

struct VolumeSource {
  std::filesystem::path path;
  std::string series;  // DICOM series selection: UID, number or part of the description
};

enum class FunctionalKind { Pet, Spect, Fmri, Perfusion, Dose, Labels, Other };

struct StudyConfig {
  std::filesystem::path file;  // where it was loaded from
  std::string name;
  VolumeSource anatomical;
  std::optional<VolumeSource> functional;
  FunctionalKind functionalKind = FunctionalKind::Other;
};

StudyConfig loadStudyConfig(const std::filesystem::path& file);
std::string toString(FunctionalKind kind);

}  // namespace mvw::config
