#pragma once
// The int8 engine's detections against the fp32 engine's on the same frames, and the tolerance
// measured and documented for them (docs/cpu-detector.md, "INT8"): int8_test.cpp on the bundled
// model, model_layout_test.cpp on the decoded layout.
#include <algorithm>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "box_deviation.hpp"
#include "detector/ssd_detector.hpp"

namespace rtmot::test {

// Every fp32 detection of score >= kSure (clear of the 0.3 cut, where int8's score shifts may
// legitimately drop or add one) is looked for among the int8 detections of its class (best IoU, at
// least 0.5). Measured on x86-64 (AVX2) over the 16 reference frames: see docs/cpu-detector.md.
constexpr float kInt8Cut = 0.3F;
constexpr float kInt8Sure = 0.5F;
constexpr double kInt8MinMatchedShare = 0.95;  // of the sure fp32 detections
constexpr float kInt8MedianBoxPx = 2.F;        // median edge move of matched boxes
constexpr float kInt8MedianScore = 0.03F;      // median score change
constexpr float kInt8WorstScore = 0.2F;

struct Int8Match {
  int sure{0};
  int matched{0};
  std::vector<float> box_moves;
  std::vector<float> score_moves;

  static float median(std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  }
  float median_box() const { return median(box_moves); }
  float median_score() const { return median(score_moves); }
  float worst_box() const { return *std::max_element(box_moves.begin(), box_moves.end()); }
  float worst_score() const { return *std::max_element(score_moves.begin(), score_moves.end()); }
};

inline float iou(const tracker::Box& a, const tracker::Box& b) {
  const float iw = std::min(a.x + a.w, b.x + b.w) - std::max(a.x, b.x);
  const float ih = std::min(a.y + a.h, b.y + b.h) - std::max(a.y, b.y);
  if (iw <= 0.F || ih <= 0.F) return 0.F;
  return iw * ih / (a.area() + b.area() - iw * ih);
}

/// Runs both detectors (score cut kInt8Cut, all classes) on `frames` and matches as above.
inline Int8Match match_int8(detector::SsdDetector& fp32, detector::SsdDetector& int8,
                            const std::map<int, cv::Mat>& frames) {
  Int8Match result;
  for (const auto& [number, image] : frames) {
    std::vector<tracker::Detection> expected;
    std::vector<tracker::Detection> found;
    fp32.detect(image, number, expected);
    int8.detect(image, number, found);
    std::vector<bool> used(found.size(), false);
    for (const auto& e : expected) {  // best first (the post-processor sorts them)
      if (e.score < kInt8Sure) continue;
      ++result.sure;
      int best = -1;
      float best_iou = 0.5F;
      for (std::size_t i = 0; i < found.size(); ++i) {
        if (used[i] || found[i].class_id != e.class_id) continue;
        if (iou(found[i].box, e.box) > best_iou) {
          best_iou = iou(found[i].box, e.box);
          best = static_cast<int>(i);
        }
      }
      if (best < 0) {
        std::cout << "frame " << number << ": fp32 class " << e.class_id << " score " << e.score
                  << " at x " << e.box.x << " y " << e.box.y << " not found by int8\n";
        continue;
      }
      used[static_cast<std::size_t>(best)] = true;
      ++result.matched;
      result.box_moves.push_back(box_deviation(found[static_cast<std::size_t>(best)].box, e.box));
      result.score_moves.push_back(std::abs(found[static_cast<std::size_t>(best)].score - e.score));
    }
  }
  return result;
}

}  // namespace rtmot::test
