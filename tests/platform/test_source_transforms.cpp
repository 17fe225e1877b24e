// The source options a jetson-inference user reaches for (issue 22): --input-flip turns or mirrors
// every frame (platform/oriented_source.hpp), --input-loop plays a file again with its frame
// numbers and timestamps going on (platform/looping_source.hpp).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "platform/looping_source.hpp"
#include "platform/oriented_source.hpp"

namespace rtmot::platform {
namespace {

// A 3-wide, 2-high picture whose pixels are numbered 1..6 row by row:
//   1 2 3
//   4 5 6
cv::Mat numbered() {
  cv::Mat picture(2, 3, CV_8UC3);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) picture.at<cv::Vec3b>(y, x) = cv::Vec3b::all(1 + 3 * y + x);
  }
  return picture;
}

std::vector<std::vector<int>> rows_of(const cv::Mat& picture) {
  std::vector<std::vector<int>> rows(picture.rows);
  for (int y = 0; y < picture.rows; ++y) {
    for (int x = 0; x < picture.cols; ++x) rows[y].push_back(picture.at<cv::Vec3b>(y, x)[0]);
  }
  return rows;
}

TEST(Orientation, EveryNameTurnsOrMirrorsAsJetsonInferenceDoes) {
  using Rows = std::vector<std::vector<int>>;
  const std::vector<std::pair<Orientation, Rows>> expected = {
      {Orientation::none, {{1, 2, 3}, {4, 5, 6}}},
      {Orientation::clockwise, {{4, 1}, {5, 2}, {6, 3}}},
      {Orientation::rotate_180, {{6, 5, 4}, {3, 2, 1}}},
      {Orientation::counterclockwise, {{3, 6}, {2, 5}, {1, 4}}},
      {Orientation::horizontal, {{3, 2, 1}, {6, 5, 4}}},
      {Orientation::vertical, {{4, 5, 6}, {1, 2, 3}}},
      {Orientation::upper_left_diagonal, {{1, 4}, {2, 5}, {3, 6}}},
      {Orientation::upper_right_diagonal, {{6, 3}, {5, 2}, {4, 1}}},
  };
  ASSERT_EQ(expected.size(), kOrientationNames.entries().size());
  const cv::Mat in = numbered();
  for (const auto& [orientation, rows] : expected) {
    cv::Mat out;
    cv::Mat scratch;
    orient(in, out, orientation, scratch);
    EXPECT_EQ(rows_of(out), rows) << kOrientationNames.name(orientation);
    EXPECT_EQ(swaps_sides(orientation), out.cols != in.cols) << kOrientationNames.name(orientation);
  }
  EXPECT_EQ(kOrientationNames.parse("rotate-180"), Orientation::rotate_180);
  EXPECT_EQ(kOrientationNames.parse("upper-right-diagonal"), Orientation::upper_right_diagonal);
}

// A camera mounted sideways: the frames and the size everyone downstream reads are upright.
TEST(OrientedSource, QuarterTurnSwapsTheSizeOfFramesAndInfo) {
  OrientedSource source(open_video_source("test://smpte?width=64&height=48&num-buffers=3"),
                        Orientation::clockwise);
  EXPECT_EQ(source.info().width, 48);
  EXPECT_EQ(source.info().height, 64);
  cv::Mat frame;
  FrameInfo info;
  int frames = 0;
  while (source.read(frame, info) == ReadStatus::frame) {
    ++frames;
    EXPECT_EQ(frame.size(), cv::Size(48, 64));
    EXPECT_EQ(info.frame_number, frames);
  }
  EXPECT_EQ(frames, 3);
}

// Ten frames at 30 fps played three times: 30 frames numbered 1..30, 1/30 s apart throughout (the
// restart continues the clock), and the progress total counts every pass.
TEST(LoopingSource, FramesAndTimeGoOnAcrossPasses) {
  const auto open = [] {
    return open_video_source("test://ball?width=32&height=24&num-buffers=10");
  };
  LoopingSource source(open, 2);
  EXPECT_EQ(source.info().frame_count, 30);
  cv::Mat frame;
  FrameInfo info;
  std::vector<std::int64_t> numbers;
  std::vector<std::int64_t> pts;
  while (source.read(frame, info) == ReadStatus::frame) {
    numbers.push_back(info.frame_number);
    pts.push_back(info.pts_ns);
  }
  ASSERT_EQ(numbers.size(), 30U);
  EXPECT_EQ(source.pass(), 3);
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    EXPECT_EQ(numbers[i], static_cast<std::int64_t>(i) + 1);
    if (i > 0) {
      EXPECT_NEAR(pts[i] - pts[i - 1], 1e9 / 30.0, 1e6) << "frame " << i + 1;
    }
  }
}

TEST(LoopingSource, ForEverUntilTheReaderStops) {
  const auto open = [] {
    return open_video_source("test://ball?width=32&height=24&num-buffers=4");
  };
  LoopingSource source(open, -1);
  EXPECT_EQ(source.info().frame_count, 0) << "no total: no ETA for an endless loop";
  cv::Mat frame;
  FrameInfo info;
  for (int i = 1; i <= 21; ++i) {
    ASSERT_EQ(source.read(frame, info), ReadStatus::frame) << i;
    EXPECT_EQ(info.frame_number, i);
  }
  EXPECT_EQ(source.pass(), 6);
}

}  // namespace
}  // namespace rtmot::platform
