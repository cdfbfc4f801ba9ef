#pragma once
// A movie of rendered frames (a rotating MIP): MPEG-4 Part 2 ('mp4v') in .mp4, or Motion JPEG
// in .avi, through OpenCV's VideoWriter (FFmpeg backend) in the plugin libmvw-movie.so, loaded on
// first use (src/movie/MoviePlugin.h). The file appears whole or not at all:
// it is written under a temporary name and renamed by finish(); a writer destroyed before
// finish() removes it. MPEG-4 needs even sizes, so an odd width or height is padded by one
// column or row repeating the last one (both formats, so a movie's size does not depend on it).
#include <filesystem>
#include <memory>

#include "mvw/core/Image.h"

namespace mvw::io {

class MovieWriter {
 public:
  // Throws mvw::Error naming `path` when no encoder is available or the extension is neither
  // .mp4 nor .avi.
  MovieWriter(const std::filesystem::path& path, int width, int height, double framesPerSecond);
  ~MovieWriter();
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  // Every frame has the size given to the constructor.
  void add(const Image& frame);
  void finish();
  int frames() const;
  // The size the movie holds (even).
  int width() const;
  int height() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct MovieInfo {
  int frames = 0;  // decoded, not the container's claim
  int width = 0, height = 0;
};
// Decodes every frame of a movie (tests, checks); throws mvw::Error if it cannot be opened.
MovieInfo readMovieInfo(const std::filesystem::path& path);

}  // namespace mvw::io
