#include "motio/track_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "common/input_error.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::motio {

namespace fs = std::filesystem;

FrameDetections load_detections(const fs::path& file, const SequenceInfo& info) {
  if (file.filename() != "gt.txt") {
    return FrameDetections(read_mot_file(file, MotFileKind::detections, info.length));
  }
  // Ground truth as a perfect detector: only what the benchmark scores, at full confidence.
  std::vector<MotRow> rows = read_mot_file(file, MotFileKind::ground_truth, info.length);
  std::vector<MotRow> kept;
  kept.reserve(rows.size());
  for (MotRow row : rows) {
    if (row.conf == 0.F || (row.class_id >= 0 && row.class_id != 1)) continue;
    row.id = -1;
    row.conf = 1.F;
    kept.push_back(row);
  }
  return FrameDetections(kept);
}

TrackRun track_sequence(const fs::path& sequence_dir, const TrackOptions& options,
                        const ProgressCallback& progress) {
  const SequenceInfo info = read_seqinfo(sequence_dir / "seqinfo.ini");
  return track_detections(load_detections(sequence_dir / options.detections, info), info, options,
                          progress);
}

TrackRun track_detections(const FrameDetections& detections, const SequenceInfo& info,
                          const TrackOptions& options, const ProgressCallback& progress) {
  if (options.interval < 1 || options.interval > kMaxFrame) {
    throw InputError("", 0, "interval", "must be in [1, " + std::to_string(kMaxFrame) + "]",
                     ExitCode::usage);
  }
  TrackRun run;
  run.info = info;
  tracker::TrackerConfig config = options.config;
  config.frame_rate = info.frame_rate;
  config.image_width = static_cast<float>(info.width);
  config.image_height = static_cast<float>(info.height);
  tracker::Tracker tracker(config, options.extension
                                       ? options.extension()
                                       : std::unique_ptr<tracker::TrackerExtension>());

  std::vector<tracker::TrackReport> predicted;
  if (options.predict_skipped) predicted.reserve(static_cast<std::size_t>(config.max_tracks));
  const auto add_rows = [&run](std::int64_t frame,
                               const std::vector<tracker::TrackReport>& reports) {
    for (const auto& report : reports) {
      MotRow row;
      row.frame = static_cast<int>(frame);
      row.id = report.id;
      row.box = report.box;
      row.conf = report.score;
      run.tracks.push_back(row);
    }
  };
  using Clock = std::chrono::steady_clock;
  Clock::duration in_update{};
  for (std::size_t i = 1; i < options.frames.size(); ++i) {
    if (options.frames[i] <= options.frames[i - 1]) {
      throw InputError("", 0, "frames", "must ascend", ExitCode::usage);
    }
  }
  if (!options.frames.empty() &&
      (options.frames.front() < 1 || options.frames.back() > info.length)) {
    throw InputError("", 0, "frames", "must lie in 1.." + std::to_string(info.length),
                     ExitCode::usage);
  }
  // The listed frames, or 1, 1 + interval, ... (64-bit: frame + interval cannot overflow).
  std::size_t listed = 0;
  const auto next_frame = [&](std::int64_t frame) -> std::int64_t {
    if (options.frames.empty()) return frame + options.interval;
    return listed < options.frames.size() ? options.frames[listed++] : info.length + 1;
  };
  for (std::int64_t frame = options.frames.empty() ? 1 : next_frame(0); frame <= info.length;
       frame = next_frame(frame)) {
    if (options.stop != nullptr && options.stop->load(std::memory_order_acquire)) {
      run.stopped = true;
      break;
    }
    if (options.predict_skipped && !run.processed_frames.empty()) {
      for (std::int64_t skipped = run.processed_frames.back() + 1; skipped < frame; ++skipped) {
        tracker.predict_reported_at(static_cast<double>(skipped - 1) / info.frame_rate, predicted,
                                    options.predict_min_hits);
        add_rows(skipped, predicted);
        ++run.frames_predicted;
      }
    }
    const double time = static_cast<double>(frame - 1) / info.frame_rate;
    const auto& in_frame = detections.at(frame);
    if (in_frame.size() > static_cast<std::size_t>(config.max_detections)) {
      ++run.frames_over_capacity;
      run.most_detections = std::max(run.most_detections, in_frame.size());
    }
    const auto start = Clock::now();
    const auto& reports = tracker.update(in_frame, time);
    in_update += Clock::now() - start;
    add_rows(frame, reports);
    ++run.frames_processed;
    run.processed_frames.push_back(static_cast<int>(frame));
    if (progress) progress(static_cast<int>(frame), info.length);
  }
  run.update_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(in_update).count();
  return run;
}

}  // namespace rtmot::motio
