// Golden images through the shipped CLI: `mvw render` on a generated study config with the
// views of tests/render/golden_views.json, compared with tests/render/golden/*.png.
#include <cmath>
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "../unit/TestUtil.h"

namespace mvw {
namespace {

namespace fs = std::filesystem;

TEST(GoldenRender, EveryModeMatchesItsReference) {
  const fs::path source = fs::path(MVW_SOURCE_DIR) / "tests/render";
  const fs::path work = test::scratchDir();
  nlohmann::json study = nlohmann::json::parse(std::ifstream(source / "golden_views.json"));
  study["name"] = "golden suite";
  study["anatomical"] = {{"path", test::sampleData("cranium/cranium.nii.gz").string()}};
  std::ofstream(work / "study.json") << study.dump(2);
  const std::string cmd = std::string(MVW_BINARY) + " render '" + (work / "study.json").string() + "' -o '" +
                          (work / "out").string() + "' 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const bool update = std::getenv("MVW_UPDATE_GOLDENS") != nullptr;
  const fs::path artefacts = fs::path(MVW_BINARY_DIR) / "golden-failures";
  int compared = 0;
  for (const auto& view : study["render"]["views"]) {
    const std::string name = view["name"];
    const fs::path actualPath = work / "out" / (name + ".png"), goldenPath = source / "golden" / (name + ".png");
    const cv::Mat actual = cv::imread(actualPath.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(actual.empty()) << actualPath;
    if (update) {
      fs::copy_file(actualPath, goldenPath, fs::copy_options::overwrite_existing);
      continue;
    }
    const cv::Mat golden = cv::imread(goldenPath.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(golden.empty()) << goldenPath << " missing (MVW_UPDATE_GOLDENS=1 makes it)";
    ASSERT_EQ(actual.size(), golden.size()) << name;
    cv::Mat diff;
    cv::absdiff(actual, golden, diff);
    double maxDelta = 0;
    cv::minMaxLoc(diff.reshape(1), nullptr, &maxDelta);
    const cv::Scalar mean = cv::mean(diff);
    const double meanDelta = (mean[0] + mean[1] + mean[2]) / 3.0;
    const double psnr = cv::PSNR(actual, golden);
    cv::Mat big;
    cv::compare(diff.reshape(1), 24, big, cv::CMP_GT);
    const double bigFraction = cv::countNonZero(big) / static_cast<double>(big.total());
    const bool ok = meanDelta <= 0.5 && bigFraction <= 0.001 && psnr >= 40.0;
    std::cout << name << ": max delta " << maxDelta << ", mean " << meanDelta << ", PSNR " << psnr << " dB\n";
    if (!ok) {
      fs::create_directories(artefacts);
      fs::copy_file(actualPath, artefacts / (name + ".actual.png"), fs::copy_options::overwrite_existing);
      cv::imwrite((artefacts / (name + ".diff.png")).string(), diff * 8);
    }
    EXPECT_TRUE(ok) << name << " differs from its golden image (see " << artefacts << ")";
    ++compared;
  }
  if (update) GTEST_SKIP() << "golden images rewritten: look at them before committing";
  EXPECT_EQ(compared, static_cast<int>(study["render"]["views"].size()));
}

}  // namespace
}  // namespace mvw
