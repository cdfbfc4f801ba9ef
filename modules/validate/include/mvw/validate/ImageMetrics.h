#pragma once
// Image comparison for validation and benchmarks: the only PSNR and SSIM of the product.
// Identical images have an infinite PSNR (reported as "inf").
#include <filesystem>

#include <opencv2/core.hpp>

#include "mvw/core/Image.h"

namespace mvw::validate {

// 10 log10(255^2 / mse); +infinity for mse == 0.
double psnrFromMse(double mse);

// PSNR over the R, G and B channels of two frames of the same size.
double psnr(const Image& a, const Image& b);

// Grey-level SSIM (Wang, Bovik, Sheikh, Simoncelli 2004): 11x11 Gaussian window, sigma 1.5,
// K1 0.01, K2 0.03, L 255, mean over the window positions inside the image. BGR or grey.
double ssimGrey(const cv::Mat& a, const cv::Mat& b);

// |delta| x 8 on the inferno scale; identical pixels stay black. perPixelDelta: CV_8U.
cv::Mat heatMap(const cv::Mat& perPixelDelta);

struct Metrics {
  double maxDelta = 0;      // largest channel delta of any pixel (0..255)
  double overFraction = 0;  // fraction of pixels whose largest channel delta > threshold
  double meanDelta = 0;     // mean absolute channel delta
  double psnr = 0;          // dB
  double ssim = 0;
  cv::Mat heat;  // heatMap of the per-pixel largest channel delta
};

// `actual` and `reference`: 8-bit images of one size and channel count.
Metrics compareImages(const cv::Mat& actual, const cv::Mat& reference, double deltaThreshold);

// A BGR or grey cv::Mat written as PNG (atomically, through io::writePng).
void writeMatPng(const cv::Mat& m, const std::filesystem::path& path);

}  // namespace mvw::validate
