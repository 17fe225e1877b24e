// An image's size read from its header (platform/image_header.hpp) agrees with what OpenCV's
// decoders make of real files of every format the image folder plays, odd sizes included; a cut or
// foreign header is no size; sizes beyond a frame's limits are refused before decoding.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "platform/image_header.hpp"

namespace rtmot::platform {
namespace {

std::string encoded(const std::string& extension, int width, int height) {
  const bool grey = extension == ".pgm";  // its writer takes one channel only
  cv::Mat image(height, width, grey ? CV_8UC1 : CV_8UC3, cv::Scalar(30, 120, 200));
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes)) << extension;
  return std::string(bytes.begin(), bytes.end());
}

TEST(ImageHeader, SizesOfEveryPlayedFormatMatchTheDecoder) {
  for (const char* extension : {".png", ".jpg", ".bmp", ".ppm", ".pgm"}) {
    for (const auto& [width, height] :
         std::vector<std::pair<int, int>>{{33, 17}, {1, 1}, {640, 480}}) {
      const std::string bytes = encoded(extension, width, height);
      const auto size = read_image_size(bytes);
      ASSERT_TRUE(size) << extension << " " << width << "x" << height;
      const cv::Mat decoded = cv::imdecode(
          cv::Mat(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())),
          cv::IMREAD_COLOR);
      EXPECT_EQ(size->width, decoded.cols) << extension;
      EXPECT_EQ(size->height, decoded.rows) << extension;
    }
  }
}

TEST(ImageHeader, CutOrForeignHeadersHaveNoSize) {
  const std::string png = encoded(".png", 64, 48);
  EXPECT_FALSE(read_image_size(png.substr(0, 20)));  // IHDR cut
  const std::string jpeg = encoded(".jpg", 64, 48);
  EXPECT_FALSE(read_image_size(jpeg.substr(0, 40)));  // before its start-of-frame
  EXPECT_FALSE(read_image_size(""));
  EXPECT_FALSE(read_image_size("GIF89a........"));
  EXPECT_FALSE(read_image_size("P6\n# only a comment"));
}

TEST(ImageHeader, FramesBeyondTheLimitsAreRefused) {
  EXPECT_EQ(check_image_size({640, 480}), "");
  EXPECT_EQ(check_image_size({8192, 8192}), "");
  EXPECT_NE(check_image_size({20000, 20000}).find("20000x20000"), std::string::npos);
  EXPECT_NE(check_image_size({16385, 16}).find("16384"), std::string::npos);
  EXPECT_NE(check_image_size({16384, 8193}).find("8192x8192"), std::string::npos);
}

}  // namespace
}  // namespace rtmot::platform
