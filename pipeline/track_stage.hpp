#pragma once
// The track stage (thread rtmot-track): one Tracker per source, each fed its own source's frames on
// their pts; builds the FrameResult (stream id, sequence, dropped count) for the sink stage.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "events/event_counter.hpp"
#include "pipeline/events_mailbox.hpp"
#include "pipeline/spsc_queue.hpp"
#include "pipeline/stage_items.hpp"
#include "pipeline/thumbnail_tap.hpp"
#include "tracker/tracker.hpp"
#include "tracker/tracker_config.hpp"
#include "vision/box_follower.hpp"

namespace rtmot::pipeline {

struct TrackInput {
  tracker::TrackerConfig tracker;
  /// Lines and zones counted on this source's tracks (docs/events.md); none: nothing counted.
  events::EventsConfig events;
  std::uint32_t stream_id{0};
  /// Where a new events configuration may arrive while running (not owned); null: never.
  EventsMailbox* events_mailbox{nullptr};
  /// The source's picture size, sent with every message (a ground station's canvas); 0: unknown.
  std::uint16_t frame_width{0};
  std::uint16_t frame_height{0};
  /// Every camera frame's gray thumbnail (pipeline/thumbnail_tap.hpp; not owned): the tracks'
  /// boxes are followed through the frames the detector skipped, the skipped frames' messages
  /// (full-rate output) carry the boxes the image showed, and the tracker's priors are corrected
  /// with them before each association (docs/full-rate.md, "Observed boxes"). Null: not followed.
  SpscQueue<Thumbnail>* thumbnails{nullptr};
};

class TrackStage {
 public:
  /// `full_rate`: before each processed frame, one result per frame its source skipped since its
  /// last processed one (DetectedFrame::trail), flagged predicted, with the tracks the tracker
  /// reported last (tracker::kPredictedMinHits) at their boxes predicted for that frame's pts;
  /// where the image was followed into that frame, flagged observed too, with every track reported
  /// last (kObservedMinHits, track_stage.cpp) at the boxes the image showed (docs/full-rate.md).
  /// `keep_detections`: each processed frame's message carries the detections the tracker got
  /// (TrackedFrame::detections), copied into storage reserved for the inputs' max_detections.
  TrackStage(const std::vector<TrackInput>& inputs, SpscQueue<DetectedFrame>& input,
             std::size_t queue_capacity, bool keep_images, bool full_rate = false,
             bool keep_detections = false);

  /// Until the input ends; then, unless aborted, one last message per stream with lines or zones
  /// (end_of_stream) with the events its counter's finish() decides.
  void run(const std::atomic<bool>& abort);
  /// Always called after run(): no more results.
  void finish() { output_.close(); }
  void wake_all() { output_.wake_all(); }

  SpscQueue<TrackedFrame>& output() { return output_; }

 private:
  struct Stream {
    std::unique_ptr<tracker::Tracker> tracker;
    std::unique_ptr<events::EventCounter> counter;  // null: no lines or zones
    EventsMailbox* events_mailbox{nullptr};
    std::uint32_t events_generation{0};  // of the configuration counted now (0: the run's own)
    std::uint32_t stream_id{0};
    std::uint16_t frame_width{0};
    std::uint16_t frame_height{0};
    std::int64_t messages{0};          // frames and outage ticks sent
    std::int64_t frames_processed{0};  // real frames
    std::int64_t frames_predicted{0};  // skipped frames sent with predictions (full_rate)
    // The last real frame's, for the end of the stream's message.
    std::int64_t last_frame_number{0};
    std::int64_t last_pts_ns{0};
    std::uint32_t last_frames_dropped{0};

    // Following the image (TrackInput::thumbnails); all null/empty when not followed.
    SpscQueue<Thumbnail>* thumbnails{nullptr};
    std::unique_ptr<vision::BoxFollower> follower;
    std::int64_t followed_frame{0};  // the follower's latest frame (0: none)
    // The tracks being followed, at followed_frame: those matched at the last processed frame
    // whose boxes the image has followed since. Reserved for max_tracks: no allocation.
    std::vector<tracker::ObservedBox> followed;
    std::vector<float> followed_confidence;  // of each of `followed`, its last step's
    std::vector<tracker::Box> boxes;         // scratch for the follower
    std::vector<vision::FollowedBox> moved;  // scratch for the follower

    /// Frames before `frame_number` that did not become a processed message: dropped somewhere.
    std::uint32_t dropped_before(std::int64_t frame_number) const;
    /// The header every message of the stream carries, in one place: the stream, the run (a
    /// restarted board: a new run id), the stream's next sequence number, the frame, its size and
    /// its time; the kind flags cleared, for the caller to set the one that applies.
    void stamp(messages::FrameResult& result, std::int64_t frame_number, std::int64_t pts_ns,
               std::uint32_t frames_dropped);
  };

  void finish_streams(const std::atomic<bool>& abort);
  bool send_predicted(const DetectedFrame& in, Stream& stream, const std::atomic<bool>& abort);
  /// Takes the stream's thumbnails up to `frame_number`, following its boxes frame by frame;
  /// whether the follower's latest frame is then `frame_number` with boxes still followed.
  static bool follow_until(Stream& stream, std::int64_t frame_number);
  /// After a processed frame: follow the tracks it matched from there.
  static void start_following(Stream& stream);
  /// An observed message's tracks: the predicted ones, where followed at the boxes the image
  /// showed, each scored by how well it was followed (0: not followed, its box predicted).
  static void apply_followed(const Stream& stream, std::vector<tracker::TrackReport>& tracks);

  SpscQueue<DetectedFrame>& input_;
  const bool keep_images_;
  const bool full_rate_;
  const bool keep_detections_;
  std::vector<Stream> streams_;  // written by the track thread only
  SpscQueue<TrackedFrame> output_;
};

}  // namespace rtmot::pipeline
