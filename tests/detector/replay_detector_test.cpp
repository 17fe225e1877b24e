// The replay detector serves a MOT15 det.txt frame by frame.
#include "detector/replay_detector.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "common/input_error.hpp"
#include "shared_data.hpp"

namespace rtmot::detector {
namespace {

TEST(ReplayDetector, ServesEachFramesDetectionsAboveTheThreshold) {
  const auto path = test::shared_path("data/mot15-train/TUD-Campus/det/det.txt");
  RTMOT_REQUIRE_FILE(path);
  constexpr float kThreshold = 0.9F;
  // Independent count of the file's rows per frame (frame,id,x,y,w,h,score,...).
  std::map<int, int> expected;
  std::map<int, float> first_x;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    int frame = 0, id = 0;
    float x = 0, y = 0, w = 0, h = 0, score = 0;
    fields >> frame >> id >> x >> y >> w >> h >> score;
    if (score < kThreshold) continue;
    ++expected[frame];
    if (!first_x.count(frame)) first_x[frame] = x;
  }
  ASSERT_FALSE(expected.empty());

  ReplayDetector detector(path, kThreshold);
  EXPECT_EQ(detector.last_frame(), expected.rbegin()->first);
  std::vector<tracker::Detection> out;
  int total = 0;
  for (int frame = 0; frame <= detector.last_frame() + 2; ++frame) {
    detector.detect(cv::Mat(), frame, out);
    const auto it = expected.find(frame);
    ASSERT_EQ(static_cast<int>(out.size()), it == expected.end() ? 0 : it->second)
        << "frame " << frame;
    for (const auto& d : out) {
      EXPECT_EQ(d.class_id, 1);
      EXPECT_GE(d.score, kThreshold);
    }
    if (!out.empty()) {
      EXPECT_FLOAT_EQ(out.front().box.x, first_x[frame]);
    }
    total += static_cast<int>(out.size());
  }
  EXPECT_GT(total, 0);
}

TEST(ReplayDetector, MissingFileIsAnInputError) {
  EXPECT_THROW(ReplayDetector(test::shared_path("data/no-such/det.txt")), InputError);
}

}  // namespace
}  // namespace rtmot::detector
