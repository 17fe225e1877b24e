#pragma once
// Value types the tracker speaks: boxes, detections and what it reports per track.
#include <cstdint>

#include "tracker/appearance.hpp"
#include "tracker/track_stage.hpp"

namespace rtmot::tracker {

/// Axis-aligned box in pixels: top-left corner and size (the MOTChallenge convention).
struct Box {
  float x{0.F};
  float y{0.F};
  float w{0.F};
  float h{0.F};

  float area() const { return w * h; }
  float center_x() const { return x + 0.5F * w; }
  float center_y() const { return y + 0.5F * h; }
};

/// One detector output. `class_id` uses the detector's own ids (COCO's 91-id map for the SSD).
struct Detection {
  // Constructed from what a detector knows (`{box, score, class_id}`); the appearance, which only
  // the image layer adds, is set afterwards.
  Detection() = default;
  Detection(const Box& found, float found_score = 1.F, int found_class = 0)
      : box(found), score(found_score), class_id(found_class) {}

  Box box;
  float score{1.F};
  int class_id{0};
  Appearance appearance;  // from the image (vision/), when there is one
};

/// Where the image showed a track at an update's time (the pipeline follows boxes through the
/// frames the detector skipped: vision/box_follower.hpp). Not a detection: it moves the track's
/// motion model but neither confirms nor matches it.
struct ObservedBox {
  std::int32_t id{0};  // the track's, as reported
  Box box;
};

/// What the tracker reports for a track in one frame: update() reports the confirmed ones,
/// Tracker::track_table() every live one.
struct TrackReport {
  // 1-based; never two live tracks with one id. A new track re-identified (reid_gate) as one lost
  // or removed carries that one's id from its first report on (born partly hidden: from its first
  // clear sighting within a second of its birth; docs/appearance.md).
  std::int32_t id{0};
  Box box;                   // the filtered (posterior) box
  float score{0.F};          // score of the detection matched in this frame
  std::int32_t class_id{0};  // class of the detections that made the track
  std::int32_t hits{0};      // consecutive matched updates
  std::int32_t age{0};       // updates since the track was born
  TrackStage stage{TrackStage::confirmed};
};

}  // namespace rtmot::tracker
