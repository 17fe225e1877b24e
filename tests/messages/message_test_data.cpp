#include "message_test_data.hpp"

#include <algorithm>
#include <cstring>

#include "motio/mot_files.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

constexpr std::int64_t frame_period_ns = 33'333'333;
constexpr std::int64_t capture_origin_ns =
    5'000'000'000'000;  // a steady clock some hours after boot

std::vector<motio::MotRow> detection_rows(const std::string& sequence) {
  const auto path = shared_path("data/mot15-train/" + sequence + "/det/det.txt");
  if (!std::filesystem::exists(path)) {
    ADD_FAILURE() << "missing test data file: " << path;
    return {};
  }
  return motio::read_mot_file(path, motio::MotFileKind::detections);
}

messages::FrameResult empty_frame(std::int64_t frame_number) {
  messages::FrameResult frame;
  frame.stream_id = 7;
  frame.sequence = static_cast<std::uint64_t>(frame_number - 1);
  frame.frame_number = frame_number;
  frame.pts_ns = (frame_number - 1) * frame_period_ns;
  frame.frames_dropped = static_cast<std::uint32_t>(frame_number / 25);
  frame.times.captured_ns = capture_origin_ns + frame.pts_ns;
  frame.times.detect_start_ns = frame.times.captured_ns + 1'000'000;
  frame.times.detected_ns = frame.times.detect_start_ns + 48'000'000 + frame_number * 1'000;
  frame.times.tracked_ns = frame.times.detected_ns + 150'000;
  frame.times.sent_ns = frame.times.tracked_ns + 20'000;
  return frame;
}

tracker::TrackReport track_from(const motio::MotRow& row, std::int32_t id) {
  tracker::TrackReport track;
  track.id = id;
  track.box = row.box;
  track.score = row.conf;
  track.class_id = 1;
  track.age = row.frame;
  track.hits = std::min(row.frame, 1 + id % 17);
  return track;
}

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

std::vector<messages::FrameResult> frames_from_detections(const std::string& sequence,
                                                          std::size_t max_frames) {
  std::vector<messages::FrameResult> frames;
  std::int32_t next_id = 1;
  for (const auto& row : detection_rows(sequence)) {
    if (static_cast<std::size_t>(row.frame) > max_frames) break;
    while (frames.size() < static_cast<std::size_t>(row.frame)) {
      frames.push_back(empty_frame(static_cast<std::int64_t>(frames.size()) + 1));
    }
    frames.back().tracks.push_back(track_from(row, next_id++));
  }
  return frames;
}

messages::FrameResult crowd_from_detections(const std::string& sequence, std::size_t track_count) {
  messages::FrameResult frame = empty_frame(1);
  std::int32_t next_id = 1;
  for (const auto& row : detection_rows(sequence)) {
    if (frame.tracks.size() == track_count) break;
    frame.tracks.push_back(track_from(row, next_id++));
  }
  if (frame.tracks.size() != track_count) {
    ADD_FAILURE() << sequence << " has fewer than " << track_count << " detections";
  }
  return frame;
}

::testing::AssertionResult same_as_sent(const messages::FrameResult& sent,
                                        const messages::DecodedMessage& decoded) {
  const auto& got = decoded.frame;
  if (got.stream_id != sent.stream_id || got.sequence != sent.sequence ||
      got.frame_number != sent.frame_number || got.pts_ns != sent.pts_ns ||
      got.frames_dropped != sent.frames_dropped ||
      got.times.captured_ns != sent.times.captured_ns || got.times.sent_ns != sent.times.sent_ns) {
    return ::testing::AssertionFailure() << "header differs for sequence " << sent.sequence;
  }
  if (decoded.truncated() || decoded.total_track_count != sent.tracks.size() ||
      got.tracks.size() != sent.tracks.size()) {
    return ::testing::AssertionFailure() << "track count differs for sequence " << sent.sequence;
  }
  for (std::size_t i = 0; i < sent.tracks.size(); ++i) {
    const auto& a = sent.tracks[i];
    const auto& b = got.tracks[i];
    if (a.id != b.id || !same_bits(a.box.x, b.box.x) || !same_bits(a.box.y, b.box.y) ||
        !same_bits(a.box.w, b.box.w) || !same_bits(a.box.h, b.box.h) ||
        !same_bits(a.score, b.score) || a.class_id != b.class_id || a.hits != b.hits ||
        a.age != b.age) {
      return ::testing::AssertionFailure()
             << "track " << i << " (id " << a.id << ") differs in sequence " << sent.sequence;
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace rtmot::test
