#include "mvw/io/PngWriter.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "FileChecks.h"
#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::io {

void writePng(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0)
    throw Error(path.string() + ": refusing to write an empty image");
  const cv::Mat rgba(image.height, image.width, CV_8UC4,
                     const_cast<std::uint8_t*>(image.rgba.data()));
  cv::Mat bgra;
  cv::cvtColor(rgba, bgra, cv::COLOR_RGBA2BGRA);
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    // The temporary keeps the .png ending: imwrite chooses the codec by extension.
    bool written = false;
    try {
      written = cv::imwrite(tmp.string(), bgra);
    } catch (const cv::Exception& e) {
      throw InputError(path, std::string("cannot write the PNG: ") + e.err);
    }
    if (!written) throw InputError(path, "cannot write the PNG (disk full or not writable?)");
  });
}

}  // namespace mvw::io
