#pragma once
// The C interface between mvw_io's MovieWriter and libmvw-movie.so, the plugin that holds
// OpenCV's video I/O (VideoWriter, VideoCapture and their FFmpeg and GStreamer backends).
// The plugin is loaded (dlopen) only when a movie is written or read: linked into mvw, those
// libraries and their 230 dependencies cost every mvw process about 0.17 s of dynamic loading
// at start (docs/performance-log.md#startup-without-video-io). No C++ exception crosses this
// interface: a call that fails returns 0 or null and leaves its reason in the plugin's message.
#include <cstdint>

extern "C" {

inline constexpr int kMvwMovieAbi = 1;

struct MvwMovieApi {
  int abi;  // kMvwMovieAbi of the plugin's build
  // Opens `path` (its extension chooses the container) for frames of width x height (even)
  // with the codec named by the four characters of `fourcc`; null on failure.
  void* (*openWriter)(const char* path, const char* fourcc, double fps, int width, int height);
  // One frame of RGBA8 pixels, row 0 on top, exactly the size given to openWriter; 1 on success.
  int (*writeFrame)(void* writer, const std::uint8_t* rgba, int width, int height);
  // Flushes and closes the file; frees the writer (also after a failure).
  void (*closeWriter)(void* writer);
  // Decodes every frame of a movie; 1 with frames and the first frame's size, 0 when it cannot
  // be opened.
  int (*probe)(const char* path, int* frames, int* width, int* height);
  // The last failure's reason in this thread ("" if none known).
  const char* (*lastError)();
};

// The plugin's one exported symbol.
const MvwMovieApi* mvw_movie_api();
}
