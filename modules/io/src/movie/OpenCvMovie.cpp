// libmvw-movie.so: OpenCV's video I/O behind the C interface of MoviePlugin.h.
#include <exception>
#include <memory>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "MoviePlugin.h"

namespace {

thread_local std::string lastError;

void* openWriter(const char* path, const char* fourcc, double fps, int width, int height) {
  try {
    auto writer = std::make_unique<cv::VideoWriter>();
    const int code = cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]);
    if (!writer->open(path, cv::CAP_FFMPEG, code, fps, cv::Size(width, height)) ||
        !writer->isOpened()) {
      lastError = "its FFmpeg backend did not open the file";
      return nullptr;
    }
    return writer.release();
  } catch (const std::exception& e) {
    lastError = e.what();
    return nullptr;
  }
}

int writeFrame(void* writer, const std::uint8_t* rgba, int width, int height) {
  try {
    const cv::Mat frame(height, width, CV_8UC4, const_cast<std::uint8_t*>(rgba));
    cv::Mat bgr;
    cv::cvtColor(frame, bgr, cv::COLOR_RGBA2BGR);
    static_cast<cv::VideoWriter*>(writer)->write(bgr);
    return 1;
  } catch (const std::exception& e) {
    lastError = e.what();
    return 0;
  }
}

void closeWriter(void* writer) {
  auto* w = static_cast<cv::VideoWriter*>(writer);
  try {
    w->release();
  } catch (const std::exception& e) {
    lastError = e.what();
  }
  delete w;
}

int probe(const char* path, int* frames, int* width, int* height) {
  try {
    cv::VideoCapture capture(path, cv::CAP_FFMPEG);
    if (!capture.isOpened()) {
      lastError = "cannot open the movie";
      return 0;
    }
    *frames = 0;
    cv::Mat frame;
    while (capture.read(frame)) {
      if (*frames == 0) *width = frame.cols, *height = frame.rows;
      ++*frames;
    }
    return 1;
  } catch (const std::exception& e) {
    lastError = e.what();
    return 0;
  }
}

const char* lastErrorText() { return lastError.c_str(); }

constexpr MvwMovieApi kApi = {kMvwMovieAbi, openWriter, writeFrame,
                              closeWriter,  probe,      lastErrorText};

}  // namespace

extern "C" __attribute__((visibility("default"))) const MvwMovieApi* mvw_movie_api() {
  return &kApi;
}
