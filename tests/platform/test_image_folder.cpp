// The image-folder source (images://DIR, or a folder path): real vtest.avi frames written to a temp
// folder come back pixel for pixel (PNG), in natural file-name order, with pts from the fps option.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "common/input_error.hpp"
#include "platform/image_folder_source.hpp"
#include "platform/video_source.hpp"
#include "platform/video_uri.hpp"
#include "shared_data.hpp"

namespace rtmot::platform {
namespace {

constexpr int kFrames = 12;

class ImageFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("rtmot_images_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// The first `count` frames of vtest.avi, decoded by the GStreamer file source.
  static std::vector<cv::Mat> vtest(int count) {
    const auto path = test::shared_path("data/video/vtest.avi");
    if (!std::filesystem::exists(path)) {
      ADD_FAILURE() << "missing test data file: " << path;
      return {};
    }
    auto source = open_video_source("file://" + path.string());
    std::vector<cv::Mat> frames;
    cv::Mat image;
    FrameInfo info;
    while (static_cast<int>(frames.size()) < count &&
           source->read(image, info) == ReadStatus::frame) {
      frames.push_back(image.clone());
    }
    return frames;
  }

  std::filesystem::path dir_;
};

TEST_F(ImageFolder, PlaysRealFramesInNaturalOrderWithPts) {
  const auto frames = vtest(kFrames);
  ASSERT_EQ(static_cast<int>(frames.size()), kFrames);
  // Unpadded numbers: natural order (2 before 10) is what makes this play in sequence.
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_TRUE(cv::imwrite((dir_ / ("frame" + std::to_string(i + 1) + ".png")).string(),
                            frames[static_cast<std::size_t>(i)]));
  }
  std::ofstream(dir_ / "notes.txt") << "not an image: skipped";
  const auto source = open_video_source("images://" + dir_.string() + "?fps=12.5");
  EXPECT_EQ(source->info().width, frames[0].cols);
  EXPECT_EQ(source->info().height, frames[0].rows);
  EXPECT_DOUBLE_EQ(source->info().fps, 12.5);
  EXPECT_FALSE(source->info().live);
  cv::Mat image;
  FrameInfo info;
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_EQ(source->read(image, info), ReadStatus::frame) << source->last_error();
    EXPECT_EQ(info.frame_number, i + 1);
    EXPECT_EQ(info.pts_ns, static_cast<std::int64_t>(i) * 80'000'000);  // 1 / 12.5 s
    ASSERT_EQ(image.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(image, frames[static_cast<std::size_t>(i)], cv::NORM_INF), 0.0)
        << "frame " << i + 1;
  }
  EXPECT_EQ(source->read(image, info), ReadStatus::end_of_stream);
}

TEST_F(ImageFolder, PlainFolderPathAndLoops) {
  const auto frames = vtest(3);
  ASSERT_EQ(frames.size(), 3U);
  for (int i = 0; i < 3; ++i) {
    // Zero-padded like MOTChallenge's img1/000001.jpg; JPEG is lossy, so compare loosely.
    char name[16];
    std::snprintf(name, sizeof name, "%06d.jpg", i + 1);
    ASSERT_TRUE(cv::imwrite((dir_ / name).string(), frames[static_cast<std::size_t>(i)]));
  }
  const VideoUri uri = parse_video_uri(dir_.string());
  EXPECT_EQ(uri.kind, SourceKind::images);
  EXPECT_DOUBLE_EQ(uri.images.fps, 30.0);
  const auto source = open_video_source("images://" + dir_.string() + "?loop=2");
  cv::Mat image;
  FrameInfo info;
  for (int i = 0; i < 6; ++i) {
    ASSERT_EQ(source->read(image, info), ReadStatus::frame) << source->last_error();
    EXPECT_EQ(info.frame_number, i + 1);
    EXPECT_LT(cv::norm(image, frames[static_cast<std::size_t>(i % 3)], cv::NORM_L1) /
                  static_cast<double>(image.total() * 3),
              4.0)
        << "mean absolute JPEG error, frame " << i + 1;
  }
  EXPECT_EQ(source->read(image, info), ReadStatus::end_of_stream);
}

TEST_F(ImageFolder, EmptyOrMissingFolderFailsToOpenNamingIt) {
  for (const std::string& uri :
       {"images://" + dir_.string(), "images://" + dir_.string() + "/no"}) {
    try {
      open_video_source(uri);
      ADD_FAILURE() << "opened " << uri;
    } catch (const InputError& e) {
      EXPECT_EQ(e.exit_code(), ExitCode::source_failed) << e.what();
      EXPECT_EQ(e.file(), uri) << e.what();
    }
  }
}

TEST_F(ImageFolder, UndecodableFileIsAReadErrorNamingIt) {
  const auto frames = vtest(1);
  ASSERT_EQ(frames.size(), 1U);
  ASSERT_TRUE(cv::imwrite((dir_ / "1.png").string(), frames[0]));
  std::ofstream(dir_ / "2.png") << "truncated";
  const auto source = open_video_source("images://" + dir_.string());
  cv::Mat image;
  FrameInfo info;
  ASSERT_EQ(source->read(image, info), ReadStatus::frame);
  EXPECT_EQ(source->read(image, info), ReadStatus::error);
  EXPECT_NE(source->last_error().find("2.png"), std::string::npos) << source->last_error();
}

TEST(ImageFolderUri, ParametersAreChecked) {
  EXPECT_DOUBLE_EQ(parse_video_uri("images:///data/img1?fps=25").images.fps, 25.0);
  EXPECT_EQ(parse_video_uri("images:///data/img1?loop=3").images.loop, 3);
  EXPECT_EQ(parse_video_uri("images://a%20b").location, "a b");
  EXPECT_FALSE(is_live(parse_video_uri("images:///x")));
  for (const char* bad : {"images://", "images:///x?fps=0", "images:///x?loop=0",
                          "images:///x?speed=2", "images:///x?fps=5&fps=6"}) {
    EXPECT_THROW(parse_video_uri(bad), InputError) << bad;
  }
}

}  // namespace
}  // namespace rtmot::platform
