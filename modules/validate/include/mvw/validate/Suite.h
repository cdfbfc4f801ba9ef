#pragma once
// A validation suite file: cases that render a study's view headless and compare it with a
// reference image under tolerances, and analytic checks. The format is documented at
// `mvw validate` (app/ValidateCommand.h). Loading validates everything and throws InputError
// naming the suite file for any problem.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mvw::validate {

struct Tolerance {
  double maxDelta = 24.0;           // per-pixel channel delta (0..255) ...
  double maxDeltaFraction = 0.001;  // ... that at most this fraction of pixels may exceed
  double meanDelta = 0.5;           // mean absolute channel delta
  double psnr = 40.0;               // dB, at least
  double ssim = 0.99;               // grey-level SSIM (Wang et al. 2004), at least
};

// "mip_equals_max_projection": a MIP along a volume index axis, one ray per voxel column,
// against the maximum of the voxel values along that axis computed from the volume.
struct CheckSpec {
  std::string type;
  int axis = 2;
  std::optional<double> window, level;
  double minPsnr = 35.0;
  double maxWorst = 2.0;  // grey levels, over pixels whose voxel is unambiguous
};

struct CaseSpec {
  std::string name;
  std::filesystem::path study;
  nlohmann::json view;    // a view name of the study (string) or a view object
  std::string viewLabel;  // how the suite named it
  std::optional<std::filesystem::path> reference;
  Tolerance tolerance;
  std::vector<CheckSpec> checks;
};

struct Suite {
  std::filesystem::path file;
  std::string name;
  std::vector<CaseSpec> cases;
  // "checksums": the manifest of the goldens' pixel SHA-256 and the GL renderer they were
  // made on (Checksums.h); absent: tolerances only.
  std::optional<std::filesystem::path> checksums;
};

Suite loadSuite(const std::filesystem::path& file);

// Suite-parsing pieces, public for their unit tests.
// "${NAME}" replaced by the environment variable NAME (unset or empty: InputError).
std::string expandEnvironment(const std::string& text, const std::filesystem::path& suite,
                              const std::string& where);
// Letters, digits, '-', '_' and '.' (not first), at most 100: the name becomes a folder.
bool isGoodCaseName(const std::string& name);

}  // namespace mvw::validate
