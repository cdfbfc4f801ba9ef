#include "mvw/io/MovieWriter.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "HelperFiles.h"
#include "movie/MoviePlugin.h"
#include "mvw/core/Error.h"

namespace mvw::io {

namespace fs = std::filesystem;

namespace {

// Where libmvw-movie.so is looked for: HelperFiles.h, with $MVW_MOVIE_PLUGIN.
std::vector<fs::path> pluginCandidates() {
  return detail::helperFileCandidates("MVW_MOVIE_PLUGIN", MVW_MOVIE_PLUGIN_FILE,
                                      MVW_MOVIE_PLUGIN_BUILD_PATH, MVW_MOVIE_PLUGIN_INSTALL_PATH);
}

// The plugin, loaded once per process and never unloaded; throws mvw::InputError naming `file`
// (the movie asked for) and every place looked in when it cannot be loaded.
const MvwMovieApi& moviePlugin(const fs::path& file) {
  static const MvwMovieApi* api = nullptr;
  static std::string failure;
  static const bool loaded = [] {
    std::string tried;
    const char* chosen = std::getenv("MVW_MOVIE_PLUGIN");
    for (const fs::path& candidate : pluginCandidates()) {
      std::error_code ec;
      if (!fs::is_regular_file(candidate, ec)) {
        if (chosen && *chosen) {  // a plugin named by the user is the only one tried
          failure = "MVW_MOVIE_PLUGIN names " + candidate.string() + ", which is not a file";
          return false;
        }
        tried += (tried.empty() ? "" : ", ") + candidate.string();
        continue;
      }
      void* handle = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        const char* why = ::dlerror();
        failure = "mvw's movie plugin " + candidate.string() +
                  " does not load: " + (why ? why : "unknown reason");
        return false;
      }
      using Entry = const MvwMovieApi* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "mvw_movie_api"));
      api = entry ? entry() : nullptr;
      if (!api || api->abi != kMvwMovieAbi) {
        failure = "mvw's movie plugin " + candidate.string() + " is of another mvw build";
        api = nullptr;
        return false;
      }
      return true;
    }
    failure = std::string("mvw's movie plugin (") + MVW_MOVIE_PLUGIN_FILE +
              ") is not installed; looked in " + tried;
    return false;
  }();
  // The user's set-up (an install without the plugin, a wrong MVW_MOVIE_PLUGIN): exit 2.
  if (!loaded) throw InputError(file, "cannot encode or decode a movie: " + failure);
  return *api;
}

std::string pluginReason(const MvwMovieApi& api) {
  const char* why = api.lastError();
  return why && *why ? std::string(" (") + why + ")" : std::string();
}

}  // namespace

struct MovieWriter::Impl {
  fs::path path, tmp;
  int width = 0, height = 0;  // of the frames given
  int frames = 0;
  bool finished = false;
  const MvwMovieApi* api = nullptr;
  void* writer = nullptr;            // the plugin's; closed by finish() or the destructor
  std::vector<std::uint8_t> padded;  // a frame of the even size
};

MovieWriter::MovieWriter(const fs::path& path, int width, int height, double fps)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.width = width;
  m.height = height;
  const std::string ext = path.extension().string();
  const char* fourcc = nullptr;
  if (ext == ".mp4")
    fourcc = "mp4v";
  else if (ext == ".avi")
    fourcc = "MJPG";
  else
    throw Error(path.string() + ": a movie is .mp4 or .avi");
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192)
    throw Error(path.string() + ": movie frames must be 1..8192 pixels a side");
  // The temporary keeps the extension: the container is chosen by it.
  m.tmp =
      path.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + path.filename().string());
  m.api = &moviePlugin(path);
  m.padded.resize(static_cast<std::size_t>(width + width % 2) * (height + height % 2) * 4);
  m.writer = m.api->openWriter(m.tmp.c_str(), fourcc, fps, width + width % 2, height + height % 2);
  if (!m.writer)
    throw Error(path.string() + ": OpenCV has no working " + ext.substr(1) + " encoder" +
                pluginReason(*m.api));
}

MovieWriter::~MovieWriter() {
  if (impl_->finished) return;
  if (impl_->writer) impl_->api->closeWriter(impl_->writer);
  std::error_code ec;
  fs::remove(impl_->tmp, ec);
}

void MovieWriter::add(const Image& frame) {
  Impl& m = *impl_;
  if (frame.width != m.width || frame.height != m.height)
    throw Error(m.path.string() + ": a frame of " + std::to_string(frame.width) + " x " +
                std::to_string(frame.height) + " in a movie of " + std::to_string(m.width) + " x " +
                std::to_string(m.height));
  // An odd size is padded by repeating the last column and row.
  const int w = width(), h = height();
  const std::size_t row = static_cast<std::size_t>(frame.width) * 4;
  for (int y = 0; y < h; ++y) {
    std::uint8_t* out = m.padded.data() + static_cast<std::size_t>(y) * w * 4;
    std::memcpy(out, frame.pixel(0, std::min(y, frame.height - 1)), row);
    if (w != frame.width) std::memcpy(out + row, out + row - 4, 4);
  }
  if (!m.api->writeFrame(m.writer, m.padded.data(), w, h))
    throw Error(m.path.string() + ": the movie encoder refused a frame" + pluginReason(*m.api));
  ++m.frames;
}

void MovieWriter::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  m.api->closeWriter(m.writer);
  m.writer = nullptr;
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
  const MvwMovieApi& api = moviePlugin(path);
  MovieInfo info;
  if (!api.probe(path.c_str(), &info.frames, &info.width, &info.height))
    throw Error(path.string() + ": cannot open the movie" + pluginReason(api));
  return info;
}

}  // namespace mvw::io
