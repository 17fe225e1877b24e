#pragma once
// The tracking stage's output for one processed frame, as the message sinks receive it.
#include <cstdint>
#include <vector>

#include "events/event.hpp"
#include "tracker/box.hpp"

namespace rtmot::messages {

/// When a frame passed each point of the pipeline (platform::steady_now_ns()). 0 = not reached.
struct FrameTimes {
  std::int64_t captured_ns{0};      // the source handed the frame to us
  std::int64_t detect_start_ns{0};  // the detector took it
  std::int64_t detected_ns{0};      // the detector finished
  std::int64_t tracked_ns{0};       // the tracker finished
  std::int64_t sent_ns{0};          // the sinks were handed the message (stamped by the sink stage)
};

struct FrameResult {
  std::uint32_t stream_id{0};
  /// Which run of the sender this is: random, nonzero, chosen once per process
  /// (this_process_run_id()); a receiver that sees it change knows the sender restarted, whatever
  /// its sequence numbers say. 0: not carried (senders before the extension).
  std::uint64_t run_id{0};
  std::uint64_t sequence{0};        // 0-based count of processed frames (messages) in this run
  std::int64_t frame_number{0};     // the source's 1-based frame number
  std::int64_t pts_ns{0};           // stream timestamp of the frame
  std::uint32_t frames_dropped{0};  // frames the source produced but nobody processed, so far
  /// The source's picture size in pixels: the frame the boxes are in (a ground station draws them
  /// on a canvas of this size). 0: not known (then not sent).
  std::uint16_t frame_width{0};
  std::uint16_t frame_height{0};
  /// No picture: the live source is down and being reopened. The tracker still advanced (tracks
  /// coast), so the ground station keeps hearing from us; `tracks` is then empty.
  bool source_outage{false};
  /// The stream's last message: no picture and no tracks; it carries the events the end of the
  /// stream decided (EventCounter::finish(): tracks still inside a zone leave it, marked lost).
  /// frame_number and pts_ns are the last processed frame's.
  bool end_of_stream{false};
  /// Full-rate output (docs/full-rate.md): a frame the detector skipped; `tracks` are the tracks
  /// the last processed frame reported (matched at least twice in a row), each at its box
  /// predicted for this frame's time. They
  /// never fed back into the tracker. No events (counted on processed frames only).
  bool predicted{false};
  /// With `predicted`: the boxes were followed through the skipped frames in the image
  /// (vision/box_follower.hpp); each track's score is then the share of its points the image
  /// followed (0: not followed, its box is the prediction). docs/full-rate.md, "Observed boxes".
  bool observed{false};
  FrameTimes times;
  std::vector<tracker::TrackReport> tracks;  // reserved once; never grows in steady state
  /// Line crossings and zone visits decided in this frame (events/, docs/events.md); reserved once.
  std::vector<events::Event> events;
  /// Which events configuration of the stream `events` refer to (their indexes): 0 the run's own,
  /// then 1, 2, ... as the web page saves new ones (pipeline/events_mailbox.hpp). Not sent.
  std::uint32_t events_generation{0};
};

/// This process's run id: random and nonzero, the same for every call (drawn once).
std::uint64_t this_process_run_id();

/// A destination for track messages (UDP, binary file, JSON lines). Called from one thread only.
class TrackSink {
 public:
  virtual ~TrackSink() = default;
  virtual void write(const FrameResult& result) = 0;
  /// Makes everything written so far durable/visible (called at the end and on shutdown).
  virtual void flush() = 0;
};

}  // namespace rtmot::messages
