// The imported model must reproduce the reference detections of the original TF.js model on
// vtest.avi
// (../shared/data/reference/ssdlite-coco-vtest-detections.csv: frames 1, 51, ..., 751, score >=
// 0.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "detector/ssd_detector.hpp"
#include "shared_data.hpp"

namespace rtmot::detector {
namespace {

struct Reference {
  int frame;
  tracker::Detection detection;  // box clipped to the image, as the detector reports
};

constexpr float kReferenceThreshold = 0.3F;
constexpr float kExtraAllowedBelow = 0.35F;  // unmatched detections must score under this
// The reference was made on x86-64, where this import reproduces it to 0.05 px and 5e-5. On aarch64
// OpenCV takes other SIMD (NEON) paths in decoding/resizing and in the DNN kernels, with other
// rounding: measured under qemu, boxes move by up to 3.3 px and scores by up to 0.039. There the
// test allows that much (the platforms' own agreement through the product is checked by
// scripts/cross_compare_tracks.sh, to 0.5 px and 0.005).
#if defined(__aarch64__)
constexpr float kBoxTolerancePx = 4.F;
constexpr float kScoreTolerance = 0.05F;
#else
constexpr float kBoxTolerancePx = 2.F;
constexpr float kScoreTolerance = 0.01F;
#endif
constexpr int kFirstFrame = 1;
constexpr int kFrameStep = 50;
constexpr int kLastFrame = 751;

std::vector<Reference> read_reference(const std::filesystem::path& path, int width, int height) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<Reference> rows;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    Reference r{};
    float x1 = 0, y1 = 0, x2 = 0, y2 = 0;
    fields >> r.frame >> r.detection.class_id >> r.detection.score >> x1 >> y1 >> x2 >> y2;
    EXPECT_FALSE(fields.fail()) << path << ": bad line '" << line << "'";
    x1 = std::clamp(x1, 0.F, static_cast<float>(width));
    x2 = std::clamp(x2, 0.F, static_cast<float>(width));
    y1 = std::clamp(y1, 0.F, static_cast<float>(height));
    y2 = std::clamp(y2, 0.F, static_cast<float>(height));
    r.detection.box = {x1, y1, x2 - x1, y2 - y1};
    rows.push_back(r);
  }
  return rows;
}

float iou(const tracker::Box& a, const tracker::Box& b) {
  const float iw = std::min(a.x + a.w, b.x + b.w) - std::max(a.x, b.x);
  const float ih = std::min(a.y + a.h, b.y + b.h) - std::max(a.y, b.y);
  if (iw <= 0.F || ih <= 0.F) return 0.F;
  return iw * ih / (a.area() + b.area() - iw * ih);
}

float box_deviation(const tracker::Box& a, const tracker::Box& b) {
  return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.x + a.w - b.x - b.w),
                   std::abs(a.y + a.h - b.y - b.h)});
}

TEST(SsdReference, ReproducesTheTfjsModelOnVtest) {
  const auto model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  if (!std::filesystem::exists(model)) {
    FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
  }
  const auto video_path = test::shared_path("data/video/vtest.avi");
  const auto reference_path = test::shared_path("data/reference/ssdlite-coco-vtest-detections.csv");
  RTMOT_REQUIRE_FILE(video_path);
  RTMOT_REQUIRE_FILE(reference_path);

  SsdConfig config;
  config.model_path = model;
  config.score_threshold = kReferenceThreshold;
  config.classes = {};  // all
  config.backend = BackendRequest::cpu;
  SsdDetector detector(config);

  cv::VideoCapture video(video_path.string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(video.isOpened()) << "cannot open " << video_path << " with FFmpeg";
  const int width = static_cast<int>(video.get(cv::CAP_PROP_FRAME_WIDTH));
  const int height = static_cast<int>(video.get(cv::CAP_PROP_FRAME_HEIGHT));
  const auto reference = read_reference(reference_path, width, height);
  ASSERT_FALSE(reference.empty());

  float worst_box = 0.F;
  float worst_score = 0.F;
  float best_extra = 0.F;
  int matched = 0;
  int borderline_missing = 0;
  cv::Mat image;
  std::vector<tracker::Detection> found;
  for (int frame = 1; frame <= kLastFrame; ++frame) {
    ASSERT_TRUE(video.read(image)) << "vtest.avi ended before frame " << frame;
    if ((frame - kFirstFrame) % kFrameStep != 0) continue;
    detector.detect(image, frame, found);
    std::vector<bool> used(found.size(), false);
    // Greedy matching, best reference first, per class, by IoU.
    std::vector<const Reference*> expected;
    for (const auto& r : reference) {
      if (r.frame == frame) expected.push_back(&r);
    }
    std::sort(expected.begin(), expected.end(),
              [](const auto* a, const auto* b) { return a->detection.score > b->detection.score; });
    for (const Reference* r : expected) {
      int best = -1;
      float best_iou = 0.5F;  // a match must at least overlap clearly
      for (std::size_t i = 0; i < found.size(); ++i) {
        if (used[i] || found[i].class_id != r->detection.class_id) continue;
        const float overlap = iou(found[i].box, r->detection.box);
        if (overlap > best_iou) {
          best_iou = overlap;
          best = static_cast<int>(i);
        }
      }
      if (best < 0 && r->detection.score < kReferenceThreshold + kScoreTolerance) {
        ++borderline_missing;  // within the tolerance of the cut: may legitimately fall below it
        continue;
      }
      if (best < 0) {
        ADD_FAILURE() << "frame " << frame << ": reference class " << r->detection.class_id
                      << " score " << r->detection.score << " at x " << r->detection.box.x << " y "
                      << r->detection.box.y << " not found";
        continue;
      }
      used[static_cast<std::size_t>(best)] = true;
      ++matched;
      const auto& d = found[static_cast<std::size_t>(best)];
      const float box_dev = box_deviation(d.box, r->detection.box);
      const float score_dev = std::abs(d.score - r->detection.score);
      worst_box = std::max(worst_box, box_dev);
      worst_score = std::max(worst_score, score_dev);
      EXPECT_LE(box_dev, kBoxTolerancePx) << "frame " << frame << " class " << d.class_id;
      EXPECT_LE(score_dev, kScoreTolerance) << "frame " << frame << " class " << d.class_id;
    }
    for (std::size_t i = 0; i < found.size(); ++i) {
      if (used[i]) continue;
      best_extra = std::max(best_extra, found[i].score);
      EXPECT_LT(found[i].score, kExtraAllowedBelow)
          << "frame " << frame << ": extra detection class " << found[i].class_id << " score "
          << found[i].score;
    }
  }
  EXPECT_EQ(matched + borderline_missing, static_cast<int>(reference.size()));
  EXPECT_LE(borderline_missing, 2) << "more than a couple of near-threshold references lost";
  RecordProperty("worst_box_deviation_px", std::to_string(worst_box));
  RecordProperty("worst_score_deviation", std::to_string(worst_score));
  RecordProperty("best_unmatched_score", std::to_string(best_extra));
  std::cout << "matched " << matched << "/" << reference.size() << ", worst box deviation "
            << worst_box << " px, worst score deviation " << worst_score
            << ", best unmatched score " << best_extra << "\n";
}

}  // namespace
}  // namespace rtmot::detector
