#include "pipeline/track_stage.hpp"

#include <algorithm>
#include <utility>

#include "platform/clock.hpp"

namespace rtmot::pipeline {
namespace {

constexpr std::size_t kEventsPerFrame = 64;
// Which reported tracks a skipped frame shows when the image was followed into it: every one the
// last processed frame reported (matched there), not only those matched twice in a row
// (tracker::kPredictedMinHits, the rule for predicted boxes). A track just found again is then
// where the image shows it, not a guess: chosen by docs/full-rate.md's protocol (both first
// halves at 100, 250 and 500 ms: MOTA higher in every cell, IDF1 never lower).
constexpr int kObservedMinHits = 1;

int most_tracks(const std::vector<TrackInput>& inputs) {
  int most = 0;
  for (const auto& input : inputs) most = std::max(most, input.tracker.max_tracks);
  return most;
}

int most_detections(const std::vector<TrackInput>& inputs) {
  int most = 0;
  for (const auto& input : inputs) most = std::max(most, input.tracker.max_detections);
  return most;
}

}  // namespace

std::uint32_t TrackStage::Stream::dropped_before(std::int64_t frame_number) const {
  return static_cast<std::uint32_t>(std::max<std::int64_t>(0, frame_number - 1 - frames_processed));
}

void TrackStage::Stream::stamp(messages::FrameResult& result, std::int64_t frame_number,
                               std::int64_t pts_ns, std::uint32_t frames_dropped) {
  result.stream_id = stream_id;
  result.run_id = messages::this_process_run_id();
  result.frame_width = frame_width;
  result.frame_height = frame_height;
  result.sequence = static_cast<std::uint64_t>(messages++);
  result.source_outage = false;
  result.end_of_stream = false;
  result.predicted = false;
  result.frame_number = frame_number;
  result.pts_ns = pts_ns;
  result.frames_dropped = frames_dropped;
  result.events_generation = events_generation;
}

TrackStage::TrackStage(const std::vector<TrackInput>& inputs, SpscQueue<DetectedFrame>& input,
                       std::size_t queue_capacity, bool keep_images, bool full_rate,
                       bool keep_detections)
    : input_(input),
      keep_images_(keep_images),
      full_rate_(full_rate),
      keep_detections_(keep_detections),
      output_(std::max(queue_capacity, inputs.size()), [&](TrackedFrame& item) {
        item.result.tracks.reserve(static_cast<std::size_t>(most_tracks(inputs)));
        if (keep_detections)
          item.detections.reserve(static_cast<std::size_t>(most_detections(inputs)));
        // Events are rare; a burst beyond this grows the slot once and it keeps the capacity.
        item.result.events.reserve(kEventsPerFrame);
      }) {
  streams_.reserve(inputs.size());
  for (const auto& wanted : inputs) {
    Stream stream;
    stream.tracker = std::make_unique<tracker::Tracker>(wanted.tracker);
    stream.stream_id = wanted.stream_id;
    stream.frame_width = wanted.frame_width;
    stream.frame_height = wanted.frame_height;
    stream.events_mailbox = wanted.events_mailbox;
    if (!wanted.events.lines.empty() || !wanted.events.zones.empty())
      stream.counter = std::make_unique<events::EventCounter>(wanted.events);
    if (wanted.thumbnails != nullptr) {
      stream.thumbnails = wanted.thumbnails;
      stream.follower = std::make_unique<vision::BoxFollower>();
      const auto most = static_cast<std::size_t>(wanted.tracker.max_tracks);
      stream.followed.reserve(most);
      stream.followed_confidence.reserve(most);
      stream.boxes.reserve(most);
      stream.moved.reserve(most);
    }
    streams_.push_back(std::move(stream));
  }
}

void TrackStage::run(const std::atomic<bool>& abort) {
  while (DetectedFrame* in = input_.front(abort)) {
    Stream& stream = streams_[in->input];
    if (full_rate_ && !in->outage && !send_predicted(*in, stream, abort)) return;
    TrackedFrame* out = output_.claim(abort);
    if (out == nullptr) return;
    const double seconds = static_cast<double>(in->info.pts_ns) * 1e-9;
    // With the image followed up to this frame (from the last processed one, across any frames
    // the detector skipped), the tracks it followed start the association where the image showed
    // them, not where their motion model guessed. Consecutive processed frames too, since round
    // 26 (docs/full-rate.md: chosen on the first halves of both videos and checked on the second,
    // MOTA and IDF1 higher).
    const bool followed =
        stream.follower && !in->outage && follow_until(stream, in->info.frame_number);
    const auto& reports = followed
                              ? stream.tracker->update(in->detections, seconds, stream.followed)
                              : stream.tracker->update(in->detections, seconds);
    messages::FrameResult& result = out->result;
    result.tracks.assign(reports.begin(), reports.end());  // within the reserved capacity
    result.events.clear();
    if (stream.events_mailbox != nullptr) {
      if (const PostedEvents* posted = stream.events_mailbox->take()) {
        // A new configuration counts from zero from this frame on (docs/web.md). Building the
        // counter allocates, once per save.
        const events::EventsConfig& config = posted->config;
        stream.counter = config.lines.empty() && config.zones.empty()
                             ? nullptr
                             : std::make_unique<events::EventCounter>(config);
        stream.events_generation = posted->generation;
      }
    }
    if (stream.counter && !in->outage) {
      // Counted on the pipeline's timestamps, so dwell and the lost timeout run on time.
      const auto& decided = stream.counter->update(reports, seconds);
      result.events.assign(decided.begin(), decided.end());
    }
    stream.stamp(result, in->info.frame_number, in->info.pts_ns,
                 stream.dropped_before(in->info.frame_number));
    result.source_outage = in->outage;
    result.times = in->times;
    result.times.tracked_ns = platform::steady_now_ns();
    out->input = in->input;
    if (keep_images_) std::swap(out->image, in->image);
    // Within the slot's reserved capacity while a frame has at most max_detections (the
    // detect stage reserves the same; the tracker itself takes no more).
    if (keep_detections_) out->detections.assign(in->detections.begin(), in->detections.end());
    if (!in->outage) {
      ++stream.frames_processed;
      stream.last_frame_number = result.frame_number;
      stream.last_pts_ns = result.pts_ns;
      stream.last_frames_dropped = result.frames_dropped;
      if (stream.follower) start_following(stream);
    }
    input_.pop();
    output_.publish();
  }
  if (!abort.load(std::memory_order_acquire)) finish_streams(abort);
}

// The frames of `in`'s trail after the stream's last processed frame and before `in`, in frame
// order: each a message with the tracker's predictions for its time, asked of the state the last
// processed frame left (causal, and Tracker::predict_reported_at changes nothing). Not counted as
// processed; no events.
bool TrackStage::send_predicted(const DetectedFrame& in, Stream& stream,
                                const std::atomic<bool>& abort) {
  for (std::size_t i = 0; i < in.trail.size(); ++i) {
    const FrameStamp& skipped = in.trail[i];
    if (skipped.frame_number <= stream.last_frame_number ||
        skipped.frame_number >= in.info.frame_number) {
      continue;
    }
    TrackedFrame* out = output_.claim(abort);
    if (out == nullptr) return false;
    messages::FrameResult& result = out->result;
    // Into the slot's reserved track storage: no allocation.
    const bool observed = stream.follower && follow_until(stream, skipped.frame_number);
    stream.tracker->predict_reported_at(static_cast<double>(skipped.pts_ns) * 1e-9, result.tracks,
                                        observed ? kObservedMinHits : tracker::kPredictedMinHits);
    if (observed) apply_followed(stream, result.tracks);
    result.events.clear();
    stream.stamp(result, skipped.frame_number, skipped.pts_ns,
                 stream.dropped_before(skipped.frame_number));
    result.predicted = true;
    result.observed = observed;
    out->detections.clear();
    result.times = messages::FrameTimes{};
    result.times.captured_ns = skipped.capture_ns;
    result.times.tracked_ns = platform::steady_now_ns();
    out->input = in.input;
    output_.publish();
    ++stream.frames_predicted;
  }
  return true;
}

bool TrackStage::follow_until(Stream& stream, std::int64_t frame_number) {
  while (const Thumbnail* next = stream.thumbnails->try_front()) {
    if (next->info.frame_number > frame_number) break;
    // A frame missing in between (lost by the source, or its thumbnail dropped): the image cannot
    // say where a box went across it.
    if (stream.followed_frame == 0 || next->info.frame_number != stream.followed_frame + 1) {
      stream.follower->reset();
      stream.followed.clear();
      stream.followed_confidence.clear();
    }
    stream.follower->push(next->gray, next->scale);
    stream.followed_frame = next->info.frame_number;
    if (!stream.followed.empty() && stream.follower->ready()) {
      stream.boxes.clear();
      for (const tracker::ObservedBox& box : stream.followed) stream.boxes.push_back(box.box);
      stream.follower->follow(stream.boxes, stream.moved);
      // A box the image lost is not followed any further: its track goes back to its prediction.
      std::size_t kept = 0;
      for (std::size_t i = 0; i < stream.followed.size(); ++i) {
        if (!stream.moved[i].followed) continue;
        stream.followed[kept] = {stream.followed[i].id, stream.moved[i].box};
        stream.followed_confidence[kept] = stream.moved[i].confidence;
        ++kept;
      }
      stream.followed.resize(kept);
      stream.followed_confidence.resize(kept);
    }
    stream.thumbnails->pop();
  }
  return stream.followed_frame == frame_number && !stream.followed.empty();
}

void TrackStage::start_following(Stream& stream) {
  stream.followed.clear();
  stream.followed_confidence.clear();
  if (stream.followed_frame != stream.last_frame_number) return;  // no picture of this frame
  for (const tracker::TrackReport& track : stream.tracker->track_table()) {
    if (track.stage != tracker::TrackStage::confirmed) continue;
    stream.followed.push_back({track.id, track.box});
    stream.followed_confidence.push_back(1.F);
  }
}

void TrackStage::apply_followed(const Stream& stream, std::vector<tracker::TrackReport>& tracks) {
  for (tracker::TrackReport& track : tracks) {
    track.score = 0.F;
    for (std::size_t i = 0; i < stream.followed.size(); ++i) {
      if (stream.followed[i].id != track.id) continue;
      track.box = stream.followed[i].box;
      track.score = stream.followed_confidence[i];
      break;
    }
  }
}

void TrackStage::finish_streams(const std::atomic<bool>& abort) {
  // The input ended (end of file, or a stop asked for): each counted stream's counter settles
  // what is still open, the tracks still inside a zone leave it marked lost (occupancy must not
  // keep a stream that is gone, and their time inside is reported), and one last message carries
  // it. Once per run, so it may allocate (a burst of events beyond the slot's reserve).
  for (std::size_t i = 0; i < streams_.size(); ++i) {
    Stream& stream = streams_[i];
    if (!stream.counter || stream.frames_processed == 0) continue;
    TrackedFrame* out = output_.claim(abort);
    if (out == nullptr) return;
    const auto& decided = stream.counter->finish(static_cast<double>(stream.last_pts_ns) * 1e-9);
    messages::FrameResult& result = out->result;
    result.tracks.clear();
    result.events.assign(decided.begin(), decided.end());
    stream.stamp(result, stream.last_frame_number, stream.last_pts_ns, stream.last_frames_dropped);
    result.end_of_stream = true;
    out->detections.clear();
    result.times = messages::FrameTimes{};
    result.times.captured_ns = platform::steady_now_ns();
    result.times.tracked_ns = result.times.captured_ns;
    out->input = i;
    out->image = cv::Mat();
    output_.publish();
  }
}

}  // namespace rtmot::pipeline
