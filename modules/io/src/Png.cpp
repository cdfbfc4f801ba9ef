#include "mvw/io/Png.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "FileChecks.h"
#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::io {

namespace fs = std::filesystem;

namespace {

// libpng reports a failure by calling its error function, which must not return: it records
// the message and jumps back to the setjmp of decode() or encode(). Those functions keep no
// object with a destructor in their own frame; whatever they fill is owned by the caller.
struct PngState {
  std::string error;
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  static_cast<PngState*>(png_get_error_ptr(png))->error = message ? message : "unknown error";
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}  // a warning is not a refusal

using File = std::unique_ptr<FILE, int (*)(FILE*)>;

bool encode(png_structp png, png_infop info, FILE* file, const Image* image, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image->width),
               static_cast<png_uint_32>(image->height), 8, PNG_COLOR_TYPE_RGB_ALPHA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 1);  // speed over size: renders are written often
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  return true;
}

}  // namespace

void writePng(const Image& image, const fs::path& path) {
  if (image.width <= 0 || image.height <= 0)
    throw Error(path.string() + ": refusing to write an empty image");
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.pixel(0, y));
  writeAtomically(path, [&](const fs::path& tmp) {
    PngState state;
    File file(std::fopen(tmp.c_str(), "wb"), &std::fclose);
    if (!file) throw InputError(path, "cannot write the PNG (the folder is not writable?)");
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onPngError, onPngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    const bool written = info && encode(png, info, file.get(), &image, rows.data());
    png_destroy_write_struct(&png, &info);
    const bool closed = std::fclose(file.release()) == 0;
    if (!written || !closed)
      throw InputError(
          path, "cannot write the PNG" +
                    (state.error.empty() ? std::string(" (disk full?)") : ": " + state.error));
  });
}

namespace {

// The signature and the IHDR chunk's size, read before libpng sees the file.
void checkHeader(const fs::path& path) {
  const std::uintmax_t size = detail::regularFileSize(path);
  std::array<unsigned char, 24> head{};
  std::ifstream in(path, std::ios::binary);
  if (size < head.size() || !in.read(reinterpret_cast<char*>(head.data()), head.size()))
    throw InputError(path, "not a PNG (shorter than a PNG header)");
  static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                              '\r', '\n', 0x1a, '\n'};
  if (!std::equal(kSignature.begin(), kSignature.end(), head.begin()))
    throw InputError(path, "not a PNG (no PNG signature)");
  if (std::memcmp(head.data() + 12, "IHDR", 4) != 0)
    throw InputError(path, "not a PNG (its first chunk is not IHDR)");
  const auto be32 = [&](std::size_t at) {
    return (std::uint32_t{head[at]} << 24) | (std::uint32_t{head[at + 1]} << 16) |
           (std::uint32_t{head[at + 2]} << 8) | std::uint32_t{head[at + 3]};
  };
  const std::uint32_t width = be32(16), height = be32(20);
  if (width == 0 || height == 0) throw InputError(path, "the PNG header declares an empty image");
  if (width > static_cast<std::uint32_t>(kMaxPngSide) ||
      height > static_cast<std::uint32_t>(kMaxPngSide) ||
      static_cast<long long>(width) * height > kMaxPngPixels)
    throw InputError(path, "the PNG header declares " + std::to_string(width) + " x " +
                               std::to_string(height) + " pixels, over the limit of " +
                               std::to_string(kMaxPngSide) + " a side");
}

// Decodes into `image` as RGBA8 through libpng's transformations; `rows` is the caller's.
bool decode(png_structp png, png_infop info, FILE* file, Image* image, std::vector<png_bytep>* rows,
            PngState* state) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_user_limits(png, kMaxPngSide, kMaxPngSide);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int colourType = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) == 16) png_set_strip_16(png);  // the high byte
  if (colourType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colourType == PNG_COLOR_TYPE_GRAY) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (colourType == PNG_COLOR_TYPE_GRAY || colourType == PNG_COLOR_TYPE_GRAY_ALPHA)
    png_set_gray_to_rgb(png);
  png_set_filler(png, 0xFF, PNG_FILLER_AFTER);  // alpha 255 where the file has none
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != static_cast<std::size_t>(width) * 4) {
    state->error = "unexpected sample layout";
    return false;
  }
  *image = Image(static_cast<int>(width), static_cast<int>(height));
  rows->resize(height);
  for (png_uint_32 y = 0; y < height; ++y) (*rows)[y] = image->pixel(0, static_cast<int>(y));
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

Image readPng(const fs::path& path) {
  checkHeader(path);
  File file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path, "cannot open the PNG");
  PngState state;
  Image image;
  std::vector<png_bytep> rows;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool decoded = info && decode(png, info, file.get(), &image, &rows, &state);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!decoded)
    throw InputError(path, "cannot decode the PNG: " +
                               (state.error.empty() ? std::string("damaged") : state.error));
  return image;
}

}  // namespace mvw::io
