// The score cut changed while the detect stage runs (pipeline/score_cut.hpp): the boxes of every
// batch handed on after a change are cut by the new value, those before by the old; at the cut the
// detector started with nothing is removed (not even a box under it, as a tile's may be). The cut
// is set from the detect thread here (by the detector, between two batches) so that which frame
// sees which value is known; tests/system/web_reload.sh sets it from an HTTP worker on a real run.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "pipeline/detect_stage.hpp"

namespace rtmot::pipeline {
namespace {

// Three boxes per picture (scores 0.2, 0.5, 0.8); sets the cut when it reaches given frames.
class ThreeBoxes : public detector::Detector {
 public:
  ThreeBoxes(ScoreCut& cut) : cut_(cut) {}
  void detect(const cv::Mat&, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    if (frame_number == 5) cut_.set(0.6F);
    if (frame_number == 8) cut_.set(cut_.floor());
    out.clear();
    for (const float score : {0.2F, 0.5F, 0.8F}) out.push_back({{0.F, 0.F, 4.F, 4.F}, score, 1});
  }
  std::string describe() const override { return "three boxes"; }

 private:
  ScoreCut& cut_;
};

TEST(LiveScoreCut, EachBatchIsCutByTheValueSetBeforeItWasHandedOn) {
  ScoreCut cut(0.3F);
  WakeSignal frames_ready;
  LatestFrameSlot slot(SlotMode::every_frame, &frames_ready);
  std::vector<std::unique_ptr<detector::Detector>> detectors;
  detectors.push_back(std::make_unique<ThreeBoxes>(cut));
  DetectOptions options;
  options.score_cut = &cut;
  DetectStage stage(std::move(detectors), {&slot}, frames_ready, options);
  std::atomic<bool> abort{false};
  constexpr std::int64_t kFrames = 10;
  std::thread producer([&] {
    for (std::int64_t f = 1; f <= kFrames; ++f) {
      slot.back().image.create(4, 4, CV_8UC3);
      slot.back().info.frame_number = f;
      slot.back().outage = false;
      if (!slot.publish(abort)) break;
    }
    slot.close();
  });
  std::thread detect([&] {
    stage.run(abort);
    stage.finish();
  });
  std::vector<std::size_t> boxes(kFrames + 1, 0);
  while (DetectedFrame* item = stage.output().front(abort)) {
    boxes.at(static_cast<std::size_t>(item->info.frame_number)) = item->detections.size();
    for (const auto& box : item->detections) {
      if (item->info.frame_number >= 5 && item->info.frame_number < 8) {
        EXPECT_GE(box.score, 0.6F);
      }
    }
    stage.output().pop();
  }
  detect.join();
  producer.join();
  // At the start's cut: the detector's boxes as they are (0.2 included); raised to 0.6 from frame
  // 5 on: one; back at the start's from frame 8 on: three again.
  EXPECT_EQ(boxes, (std::vector<std::size_t>{0, 3, 3, 3, 3, 1, 1, 1, 3, 3, 3}));
}

}  // namespace
}  // namespace rtmot::pipeline
