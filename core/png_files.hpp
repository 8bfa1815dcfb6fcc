// PNG files through libpng's simplified API: 16-bit grey (depth images) and 8-bit colour
// (pictures). Kept apart from OpenCV's image codecs, whose library alone loads about 140 shared
// libraries (GDAL, Poppler, HDF5, ...) into every run of the program.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace claspplan {

struct Gray16Image {
  int width = 0, height = 0;
  std::vector<std::uint16_t> pixels;  ///< row-major, width * height
};

/// Reads a 16-bit single-channel PNG as stored (no gamma conversion). Throws InputError with a
/// one-line reason for anything else.
Gray16Image read_png_gray16(const std::string& path);

/// The same from the bytes of a PNG file (`path` only names it in messages).
Gray16Image decode_png_gray16(const std::string& data, const std::string& path);

/// Writes a 16-bit single-channel PNG. Throws std::runtime_error when the file cannot be written.
void write_png_gray16(const std::string& path, const Gray16Image& image);

/// Writes an 8-bit BGR (CV_8UC3) or grey (CV_8UC1) picture as PNG. Throws std::runtime_error when
/// the file cannot be written, std::invalid_argument for another image type.
void write_png(const std::string& path, const cv::Mat& image);

}  // namespace claspplan
