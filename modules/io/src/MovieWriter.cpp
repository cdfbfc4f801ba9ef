#include "mvw/io/MovieWriter.h"

#include <unistd.h>

#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "mvw/core/Error.h"

namespace mvw::io {

namespace fs = std::filesystem;

struct MovieWriter::Impl {
  fs::path path, tmp;
  int width = 0, height = 0;  // of the frames given
  int frames = 0;
  bool finished = false;
  cv::VideoWriter writer;
};

MovieWriter::MovieWriter(const fs::path& path, int width, int height, double fps)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.width = width;
  m.height = height;
  const std::string ext = path.extension().string();
  int fourcc = 0;
  if (ext == ".mp4")
    fourcc = cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  else if (ext == ".avi")
    fourcc = cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
  else
    throw Error(path.string() + ": a movie is .mp4 or .avi");
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192)
    throw Error(path.string() + ": movie frames must be 1..8192 pixels a side");
  // The temporary keeps the extension: the container is chosen by it.
  m.tmp =
      path.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + path.filename().string());
  const cv::Size size(width + width % 2, height + height % 2);
  if (!m.writer.open(m.tmp.string(), cv::CAP_FFMPEG, fourcc, fps, size) || !m.writer.isOpened())
    throw Error(path.string() + ": OpenCV has no working " + ext.substr(1) +
                " encoder (its FFmpeg backend did not open the file)");
}

MovieWriter::~MovieWriter() {
  if (impl_->finished) return;
  impl_->writer.release();
  std::error_code ec;
  fs::remove(impl_->tmp, ec);
}

void MovieWriter::add(const Image& frame) {
  Impl& m = *impl_;
  if (frame.width != m.width || frame.height != m.height)
    throw Error(m.path.string() + ": a frame of " + std::to_string(frame.width) + " x " +
                std::to_string(frame.height) + " in a movie of " + std::to_string(m.width) + " x " +
                std::to_string(m.height));
  const cv::Mat rgba(frame.height, frame.width, CV_8UC4,
                     const_cast<std::uint8_t*>(frame.rgba.data()));
  cv::Mat bgr, padded;
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  cv::copyMakeBorder(bgr, padded, 0, m.height % 2, 0, m.width % 2, cv::BORDER_REPLICATE);
  m.writer.write(padded);
  ++m.frames;
}

void MovieWriter::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  m.writer.release();
  std::error_code ec;
  if (!fs::exists(m.tmp, ec) || fs::file_size(m.tmp, ec) == 0)
    throw Error(m.path.string() + ": the movie encoder wrote nothing");
  fs::rename(m.tmp, m.path, ec);
  if (ec) throw Error("cannot write " + m.path.string() + ": " + ec.message());
  m.finished = true;
}

int MovieWriter::frames() const { return impl_->frames; }
int MovieWriter::width() const { return impl_->width + impl_->width % 2; }
int MovieWriter::height() const { return impl_->height + impl_->height % 2; }

MovieInfo readMovieInfo(const fs::path& path) {
  cv::VideoCapture capture(path.string(), cv::CAP_FFMPEG);
  if (!capture.isOpened()) throw Error(path.string() + ": cannot open the movie");
  MovieInfo info;
  cv::Mat frame;
  while (capture.read(frame)) {
    if (info.frames == 0) info.width = frame.cols, info.height = frame.rows;
    ++info.frames;
  }
  return info;
}

}  // namespace mvw::io
