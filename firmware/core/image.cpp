#include "core/image.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.h"
#include "core/file_read.h"

namespace candela {
namespace {

struct FileCloser {
  void operator()(FILE* f) const {
    if (f) std::fclose(f);
  }
};

[[noreturn]] void png_error_fn(png_structp png, png_const_charp msg) {
  auto* what = static_cast<std::string*>(png_get_error_ptr(png));
  if (what) *what = msg;
  png_longjmp(png, 1);
}
void png_warning_fn(png_structp, png_const_charp) {}

}  // namespace

Image read_png(const std::string& path, int want_channels) {
  const std::string bytes = read_bounded_file(path, FileKind::kImage);
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw ConfigError(path, "", "expected a PNG file (bad signature)");

  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&img, bytes.data(), bytes.size()))
    throw ConfigError(path, "", std::string("unreadable PNG: ") + img.message);
  // A small file can declare a huge image (a decompression bomb): bound what it unpacks to.
  if (static_cast<uint64_t>(img.width) * img.height > kMaxPngPixels) {
    png_image_free(&img);
    throw ConfigError(path, "",
                      "a " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                          " image, more than the " + std::to_string(kMaxPngPixels >> 20) +
                          " Mpixel limit for a PNG image");
  }
  const int stored = PNG_IMAGE_SAMPLE_CHANNELS(img.format);
  const int ch = want_channels ? want_channels : stored;
  switch (ch) {
    case 1:
      img.format = PNG_FORMAT_GRAY;
      break;
    case 2:
      img.format = PNG_FORMAT_GA;
      break;
    case 3:
      img.format = PNG_FORMAT_RGB;
      break;
    default:
      img.format = PNG_FORMAT_RGBA;
      break;
  }
  Image out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.channels = ch == 1 || ch == 2 || ch == 3 ? ch : 4;
  out.pixels.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.pixels.data(), 0, nullptr)) {
    std::string msg = img.message;
    png_image_free(&img);
    throw ConfigError(path, "", "corrupt PNG: " + msg);
  }
  return out;
}

void write_png(const std::string& path, int width, int height, int channels, const uint8_t* data,
               int stride) {
  const std::string tmp = path + ".tmp";
  {
    std::unique_ptr<FILE, FileCloser> f(std::fopen(tmp.c_str(), "wb"));
    if (!f) throw RuntimeError(path + ": cannot write: " + std::strerror(errno));
    std::string what;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &what, png_error_fn, png_warning_fn);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
      png_destroy_write_struct(&png, &info);
      throw RuntimeError(path + ": out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      std::remove(tmp.c_str());
      throw RuntimeError(path + ": " + what);
    }
    png_init_io(png, f.get());
    static const int kTypes[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                 PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
    png_set_IHDR(png, info, width, height, 8, kTypes[channels], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 3);  // frame dumps: speed over size
    png_write_info(png, info);
    const size_t step =
        stride ? static_cast<size_t>(stride) : static_cast<size_t>(width) * channels;
    for (int y = 0; y < height; ++y) png_write_row(png, data + step * y);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(f.get()) != 0) {
      std::remove(tmp.c_str());
      throw RuntimeError(path + ": write failed: " + std::strerror(errno));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw RuntimeError(path + ": cannot rename into place: " + std::strerror(errno));
  }
}

void write_png(const std::string& path, const Image& image) {
  write_png(path, image.width, image.height, image.channels, image.pixels.data());
}

}  // namespace candela
