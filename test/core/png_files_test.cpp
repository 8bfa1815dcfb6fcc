// PNG files through libpng: 16-bit depth values survive exactly, also from files other tools write.
#include "core/png_files.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test/support/temp_dir.hpp"

namespace claspplan::test {
namespace {

TEST(PngFiles, SixteenBitValuesSurviveExactly) {
  TempDir dir;
  Gray16Image image;
  image.width = 5;
  image.height = 3;
  for (int i = 0; i < 15; ++i) image.pixels.push_back(static_cast<std::uint16_t>(i * 4681));
  image.pixels[7] = 65535;
  write_png_gray16(dir.file("a.png"), image);
  const Gray16Image back = read_png_gray16(dir.file("a.png"));
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.pixels, image.pixels);
}

TEST(PngFiles, ReadsSixteenBitFilesOfOtherToolsWithoutGammaChanges) {
  TempDir dir;
  cv::Mat m(2, 3, CV_16UC1);
  for (int i = 0; i < 6; ++i)
    m.at<std::uint16_t>(i / 3, i % 3) = static_cast<std::uint16_t>(1 + i * 9000);
  ASSERT_TRUE(cv::imwrite(dir.file("cv.png"), m));
  const Gray16Image back = read_png_gray16(dir.file("cv.png"));
  ASSERT_EQ(back.pixels.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(back.pixels[i], m.at<std::uint16_t>(i / 3, i % 3));
}

TEST(PngFiles, PicturesAreWrittenAndAreNoDepthImages) {
  TempDir dir;
  cv::Mat picture(4, 6, CV_8UC3, cv::Scalar(10, 20, 30));
  write_png(dir.file("p.png"), picture);
  const cv::Mat back = cv::imread(dir.file("p.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(back.type(), CV_8UC3);
  EXPECT_EQ(back.at<cv::Vec3b>(2, 3), cv::Vec3b(10, 20, 30));  // BGR order kept
  EXPECT_THROW(read_png_gray16(dir.file("p.png")), std::invalid_argument);
  EXPECT_THROW(read_png_gray16(dir.file("missing.png")), std::invalid_argument);
  EXPECT_THROW(write_png(dir.file("f.png"), cv::Mat(2, 2, CV_32FC1)), std::invalid_argument);
}

}  // namespace
}  // namespace claspplan::test
