// Following the image between detections (detector.follow_image, docs/full-rate.md, "Observed
// boxes") through the real threaded pipeline: a live camera three to six times faster than the
// detector shows a textured patch swinging left and right, which a constant-velocity prediction
// cannot keep up with. With the option, the skipped frames' messages are flagged observed and
// their boxes are where the patch is; without it they are the motion model's guesses. Runs under
// ThreadSanitizer (scripts/sanitize.sh): the thumbnails cross from the capture thread to the
// track stage.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <thread>
#include <vector>

#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"
#include "tracker/presets.hpp"

namespace rtmot::pipeline {
namespace {

constexpr std::int64_t kFrames = 150;
constexpr double kFps = 30.0;

// Where the patch is in frame `f` (1-based): swinging 40 px either side, a period of 31 frames.
cv::Rect2f patch_at(std::int64_t f) {
  const double x = 130.0 + 40.0 * std::sin(static_cast<double>(f) * 2.0 * CV_PI / 31.0);
  return {static_cast<float>(x), 60.F, 60.F, 120.F};
}

class SwingingPatchCamera : public platform::VideoSource {
 public:
  SwingingPatchCamera() : texture_(120, 60, CV_8UC3) {
    cv::RNG random(7);
    random.fill(texture_, cv::RNG::UNIFORM, 0, 256);
    info_.uri = "swinging-patch://";
    info_.live = true;
    info_.fps = kFps;
    info_.width = 320;
    info_.height = 240;
  }
  platform::ReadStatus read(cv::Mat& bgr, platform::FrameInfo& info) override {
    if (next_ > kFrames) return platform::ReadStatus::end_of_stream;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    bgr.create(240, 320, CV_8UC3);
    bgr.setTo(cv::Scalar::all(128));
    const cv::Rect2f at = patch_at(next_);
    texture_.copyTo(bgr(cv::Rect(static_cast<int>(std::lround(at.x)), 60, 60, 120)));
    info.frame_number = next_;
    info.pts_ns = static_cast<std::int64_t>(static_cast<double>(next_) * 1e9 / kFps);
    info.capture_ns = platform::steady_now_ns();
    ++next_;
    return platform::ReadStatus::frame;
  }
  const platform::SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return {}; }

 private:
  cv::Mat texture_;
  std::int64_t next_{1};
  platform::SourceInfo info_;
};

// Finds the patch where it is, slowly.
class SlowPatchDetector : public detector::Detector {
 public:
  void detect(const cv::Mat&, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const cv::Rect2f at = patch_at(frame_number);
    out.assign(1, tracker::Detection({at.x, at.y, at.width, at.height}, 0.9F, 1));
  }
  std::string describe() const override { return "slow patch"; }
};

// The same, but from its seventh frame on it misses the patch every other frame: each match then
// finds the track again (TrackReport::hits 1).
class BlinkingPatchDetector : public SlowPatchDetector {
 public:
  void detect(const cv::Mat& bgr, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    SlowPatchDetector::detect(bgr, frame_number, out);
    if (++calls_ > 6 && calls_ % 2 == 1) out.clear();
  }

 private:
  long calls_{0};
};

struct SkippedFrames {
  long with_tracks{0};  // skipped frames' messages that carry a track
  long observed{0};     // of those, flagged observed
  // Of |x - the patch's x| over their boxes: the predicted ones (option off), or those the image
  // followed (on: observed messages, tracks with a confidence).
  double median_error_px{-1.0};
};

std::vector<messages::FrameResult> run_pipeline(std::unique_ptr<detector::Detector> detector,
                                                bool follow_image) {
  test_parts::Collected collected;
  PipelineOptions options = test_parts::quiet(PlaybackMode::realtime);
  options.full_rate = true;
  options.follow_image = follow_image;
  tracker::TrackerConfig config = *tracker::find_preset(tracker::default_preset_name());
  config.frame_rate = kFps;
  {
    Pipeline pipeline(std::make_unique<SwingingPatchCamera>(), std::move(detector), config,
                      test_parts::sinks_into(collected), options);
    const std::atomic<bool> stop{false};
    pipeline.run(stop);
  }
  return std::move(collected.results);
}

SkippedFrames run(bool follow_image) {
  SkippedFrames skipped;
  std::vector<double> errors;
  for (const messages::FrameResult& result :
       run_pipeline(std::make_unique<SlowPatchDetector>(), follow_image)) {
    if (!result.predicted || result.tracks.empty()) continue;
    ++skipped.with_tracks;
    if (result.observed) ++skipped.observed;
    for (const tracker::TrackReport& track : result.tracks) {
      if (follow_image && !(result.observed && track.score > 0.F)) continue;
      errors.push_back(std::abs(track.box.x - patch_at(result.frame_number).x));
    }
  }
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    skipped.median_error_px = errors[errors.size() / 2];
  }
  return skipped;
}

TEST(FollowImage, SkippedFramesCarryTheBoxesTheImageShowed) {
  const SkippedFrames predicted = run(false);
  const SkippedFrames observed = run(true);
  std::cout << "skipped frames with a track: predicted " << predicted.with_tracks
            << " messages, median error " << predicted.median_error_px << " px; followed "
            << observed.with_tracks << " messages (" << observed.observed
            << " observed), median error " << observed.median_error_px << " px\n";
  ASSERT_GT(predicted.with_tracks, 10) << "the detector kept up: nothing was skipped";
  ASSERT_GT(observed.with_tracks, 10) << "the detector kept up: nothing was skipped";
  EXPECT_EQ(predicted.observed, 0);
  // A track is followed from each processed frame on: natively every such message is observed
  // (measured 100 %). How many is the machine's: under ThreadSanitizer (the track stage 5-15x
  // slower) 58 % were, the others predicted (a thumbnail the full ring dropped ends the
  // following until the next processed frame). What the observed ones show is asserted below.
  EXPECT_GE(observed.observed, 10);
  // Measured in 8 runs: 11.7-13.3 px predicted, 1.1-2.4 px followed (the patch is drawn at whole
  // pixels, and the boxes are followed from the tracker's posterior, which lags the swing).
  EXPECT_LT(observed.median_error_px, 4.0);
  EXPECT_LT(observed.median_error_px * 3.0, predicted.median_error_px);
}

// A track the last processed frame found again (matched once after a miss) is shown on the
// skipped frames after it where the image followed it (kObservedMinHits), at the patch; with
// predicted boxes only, it waits for a second match in a row (tracker::kPredictedMinHits).
long skipped_frames_showing_a_track_found_again(bool follow_image, double* median_error_px) {
  long showing = 0;
  bool found_again = false;  // the last processed frame reported the track with hits 1
  std::vector<double> errors;
  for (const messages::FrameResult& result :
       run_pipeline(std::make_unique<BlinkingPatchDetector>(), follow_image)) {
    if (!result.predicted) {
      found_again = result.tracks.size() == 1 && result.tracks[0].hits == 1;
      continue;
    }
    if (!found_again || result.tracks.empty()) continue;
    ++showing;
    for (const tracker::TrackReport& track : result.tracks) {
      if (result.observed && track.score > 0.F) {
        errors.push_back(std::abs(track.box.x - patch_at(result.frame_number).x));
      }
    }
  }
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    *median_error_px = errors[errors.size() / 2];
  }
  return showing;
}

TEST(FollowImage, ATrackFoundAgainIsShownWhereTheImageFollowedIt) {
  double unused = -1.0;
  EXPECT_EQ(skipped_frames_showing_a_track_found_again(false, &unused), 0);
  double median_error_px = -1.0;
  const long showing = skipped_frames_showing_a_track_found_again(true, &median_error_px);
  std::cout << "skipped frames showing a track found again: " << showing << ", median error "
            << median_error_px << " px\n";
  // Measured 48-54 natively in 3 runs; fewer where the track stage is slower (ThreadSanitizer).
  EXPECT_GE(showing, 5);
  // Measured 3.0-3.2 px (the boxes follow the posterior of a track just found again, which lags
  // the swing more); predicted boxes were 12 px off (the test above).
  EXPECT_GE(median_error_px, 0.0);
  EXPECT_LT(median_error_px, 6.0);
}

}  // namespace
}  // namespace rtmot::pipeline
