#pragma once
// The analytic MIP check ("mip_equals_max_projection"): a view whose every pixel's ray runs
// along one voxel column (index axis `axis`), sampled with nearest lookup at every voxel
// centre, so the render must equal the maximum of the column's values, computed here.
#include <filesystem>
#include <string>

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "mvw/core/Volume.h"
#include "mvw/render/Camera.h"
#include "mvw/validate/Suite.h"

namespace mvw::validate {

struct MipPlan {
  nlohmann::json view;  // the view object `mvw render` renders
  glm::ivec2 size{0};
  render::Camera camera;
  int a = 0, b = 1;  // index axes along the screen's right and up
};

// Throws InputError naming `suite` (and `where`) when the volume cannot be checked so
// (an axis oblique to LPS, an image over 8192 pixels a side).
MipPlan planMip(const Volume& volume, const CheckSpec& check, const std::filesystem::path& suite,
                const std::string& where);

struct CheckResult {
  bool pass = false;
  std::string message;
  double psnr = 0, worst = 0;
  long pixels = 0, unambiguous = 0;
};

// `rendered`: the BGR render of plan.view. expected (grey) and heat (BGR) are for the report.
CheckResult evaluateMip(const Volume& volume, const CheckSpec& check, const MipPlan& plan,
                        const cv::Mat& rendered, cv::Mat& expected, cv::Mat& heat);

}  // namespace mvw::validate
