#include "core/png_files.hpp"

#include <cstring>
#include <stdexcept>

#include <png.h>

#include "core/input_error.hpp"

namespace claspplan {
namespace {

// The simplified API's message, or a generic one.
std::string message(const png_image& image) {
  return image.message[0] != '\0' ? std::string(image.message) : std::string("libpng error");
}

png_image fresh_image() {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  return image;
}

void write_file(const std::string& path, int width, int height, png_uint_32 format,
                const void* pixels, png_int_32 row_stride) {
  png_image png = fresh_image();
  png.width = static_cast<png_uint_32>(width);
  png.height = static_cast<png_uint_32>(height);
  png.format = format;
  if (!png_image_write_to_file(&png, path.c_str(), 0, pixels, row_stride, nullptr)) {
    throw std::runtime_error(path + ": cannot write the PNG (" + message(png) + ")");
  }
}

// The header read (from a file or from memory) is finished into a 16-bit grey image.
Gray16Image finish_gray16(png_image& image, const std::string& path) {
  // Only a file that is 16-bit grey already (no colour, no alpha, no palette) is a depth image.
  if (image.format != PNG_FORMAT_LINEAR_Y) {
    png_image_free(&image);
    throw InputError(path + ": depth must be a 16-bit single-channel PNG");
  }
  Gray16Image out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
  if (!png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr)) {
    throw InputError(path + ": cannot decode the PNG (" + message(image) + ")");
  }
  return out;
}

}  // namespace

Gray16Image read_png_gray16(const std::string& path) {
  png_image image = fresh_image();
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    throw InputError(path + ": cannot decode the PNG (" + message(image) + ")");
  }
  return finish_gray16(image, path);
}

Gray16Image decode_png_gray16(const std::string& data, const std::string& path) {
  png_image image = fresh_image();
  if (!png_image_begin_read_from_memory(&image, data.data(), data.size())) {
    throw InputError(path + ": cannot decode the PNG (" + message(image) + ")");
  }
  return finish_gray16(image, path);
}

void write_png_gray16(const std::string& path, const Gray16Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    throw std::invalid_argument(path + ": malformed 16-bit image");
  }
  write_file(path, image.width, image.height, PNG_FORMAT_LINEAR_Y, image.pixels.data(), 0);
}

void write_png(const std::string& path, const cv::Mat& image) {
  if (image.empty() || (image.type() != CV_8UC3 && image.type() != CV_8UC1)) {
    throw std::invalid_argument(path + ": only 8-bit BGR or grey pictures are written as PNG");
  }
  write_file(path, image.cols, image.rows, image.channels() == 3 ? PNG_FORMAT_BGR : PNG_FORMAT_GRAY,
             image.data, static_cast<png_int_32>(image.step[0]));
}

}  // namespace claspplan
