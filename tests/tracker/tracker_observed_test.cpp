// Observed boxes (docs/full-rate.md, "Observed boxes"): where the image showed a track at an
// update's time, given to Tracker::update() beside the detections. The pipeline follows the
// tracks through the frames a slow detector skipped; the tracker only sees boxes.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "mot_detections.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {

TrackerConfig at_seven_fps() {
  TrackerConfig config = *find_preset(default_preset_name());
  config.frame_rate = 7.0;
  return config;
}

Box walker_at(float x) {
  return Box{x, 200.F, 40.F, 100.F};
}

// A person walks right 8 px a frame for 8 frames, every frame detected; then the detector is 6
// frames late while the person turned back. Its motion model expects the person 48 px further
// right; the image saw them come back. Only with the observed box is the detection the same track.
std::int32_t id_after_the_turn(bool with_observation) {
  Tracker tracker(at_seven_fps());
  float x = 100.F;
  std::int32_t id = 0;
  for (int frame = 0; frame < 8; ++frame, x += 8.F) {
    const auto& reports = tracker.update({Detection(walker_at(x), 0.9F, 1)}, frame / 7.0);
    if (!reports.empty()) id = reports.front().id;
  }
  EXPECT_NE(id, 0) << "the walker was never confirmed";
  const float turned = x - 8.F - 6 * 8.F;  // six frames back to the left
  const double later = (7 + 6) / 7.0;
  const std::vector<ObservedBox> observed{{id, walker_at(turned)}};
  const std::vector<Detection> detections{Detection(walker_at(turned), 0.9F, 1)};
  const auto& reports = with_observation ? tracker.update(detections, later, observed)
                                         : tracker.update(detections, later);
  for (const TrackReport& track : reports) {
    if (track.stage == TrackStage::confirmed) return track.id == id ? id : -track.id;
  }
  return 0;
}

TEST(ObservedBoxes, KeepTheIdOfAPersonWhoTurnedWhileTheDetectorWasLate) {
  const std::int32_t without = id_after_the_turn(false);
  const std::int32_t with = id_after_the_turn(true);
  EXPECT_LE(without, 0) << "the motion model alone kept the track: the scene proves nothing";
  EXPECT_GT(with, 0) << "the observed box did not bring the track to the detection";
}

// A person stands still, detected every frame; then the detector is 6 frames late and finds only
// the neighbour who stepped up beside them (38 px to the right, the person missed). The image saw
// the person stay. Across a 6-frame gap the IoU gate is widened for the motion model's guess
// (max_gate_margin), which reaches the neighbour; with observed_gate_frames the followed track's
// gate is that of 2 frames, and the neighbour's detection is not the person's. What the track
// with the person's id was matched to, if anything: its box's x, or -1.
float where_the_person_id_went(double observed_gate_frames) {
  TrackerConfig config = at_seven_fps();
  config.observed_gate_frames = observed_gate_frames;
  Tracker tracker(config);
  std::int32_t id = 0;
  for (int frame = 0; frame < 8; ++frame) {
    const auto& reports = tracker.update({Detection(walker_at(100.F), 0.9F, 1)}, frame / 7.0);
    if (!reports.empty()) id = reports.front().id;
  }
  EXPECT_NE(id, 0) << "the person was never confirmed";
  const std::vector<ObservedBox> observed{{id, walker_at(100.F)}};
  const std::vector<Detection> neighbour{Detection(walker_at(138.F), 0.9F, 1)};
  for (const TrackReport& track : tracker.update(neighbour, (7 + 6) / 7.0, observed)) {
    if (track.id == id) return track.box.x;
  }
  return -1.F;
}

TEST(ObservedBoxes, AFollowedTracksGateIsNotWidenedForTheWholeGap) {
  EXPECT_GT(where_the_person_id_went(0.0), 110.F)
      << "the widened gate did not reach the neighbour: the scene proves nothing";
  EXPECT_EQ(where_the_person_id_went(2.0), -1.F)
      << "the followed track took the neighbour's detection";
}

// An observation is not a detection: a track seen only in the image is not kept alive by it.
TEST(ObservedBoxes, DoNotKeepATrackWithoutDetectionsAlive) {
  TrackerConfig config = at_seven_fps();
  Tracker tracker(config);
  std::int32_t id = 0;
  for (int frame = 0; frame < 6; ++frame) {
    const auto& reports =
        tracker.update({Detection(walker_at(100.F + 8.F * frame), 0.9F, 1)}, frame / 7.0);
    if (!reports.empty()) id = reports.front().id;
  }
  ASSERT_NE(id, 0);
  bool alive = true;
  for (int frame = 6; frame < 6 + 100 && alive; ++frame) {
    const std::vector<ObservedBox> observed{{id, walker_at(100.F + 8.F * frame)}};
    tracker.update({}, frame / 7.0, observed);
    alive = false;
    for (const TrackReport& track : tracker.track_table()) alive = alive || track.id == id;
  }
  EXPECT_FALSE(alive) << "100 frames of observations without a detection kept the track";
}

// No observations: the overload is update() itself, bit for bit, on a real sequence.
TEST(ObservedBoxes, NoneLeaveTheUpdatesAsTheyWere) {
  const auto dir = test::shared_path("data/mot15-train/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(dir / "det" / "det.txt");
  const test::MotSequence sequence = test::load_mot_sequence(dir);
  TrackerConfig config = *find_preset(default_preset_name());
  config.frame_rate = sequence.frame_rate;
  Tracker plain(config);
  Tracker observing(config);
  const std::vector<ObservedBox> none;
  long compared = 0;
  for (std::size_t f = 0; f < sequence.frames.size(); ++f) {
    const double t = static_cast<double>(f) / sequence.frame_rate;
    const std::vector<TrackReport> a = plain.update(sequence.frames[f], t);
    const std::vector<TrackReport>& b = observing.update(sequence.frames[f], t, none);
    ASSERT_EQ(a.size(), b.size()) << "frame " << f;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].id, b[i].id);
      EXPECT_EQ(std::memcmp(&a[i].box, &b[i].box, sizeof(Box)), 0) << "frame " << f;
      ++compared;
    }
  }
  EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace rtmot::tracker
