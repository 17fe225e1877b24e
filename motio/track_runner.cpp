#include "motio/track_runner.hpp"

#include <chrono>

#include "common/input_error.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::motio {

namespace fs = std::filesystem;

std::vector<std::vector<tracker::Detection>> load_detections(const fs::path& file,
                                                             const SequenceInfo& info) {
  if (!fs::exists(file)) throw InputError(file.string(), 0, "", "missing detections file");
  if (file.filename() != "gt.txt") {
    return detections_by_frame(read_mot_file(file, MotFileKind::detections, info.length),
                               info.length);
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
  return detections_by_frame(kept, info.length);
}

TrackRun track_sequence(const fs::path& sequence_dir, const TrackOptions& options,
                        const ProgressCallback& progress) {
  if (options.interval < 1) {
    throw InputError("", 0, "interval", "must be at least 1", ExitCode::usage);
  }
  TrackRun run;
  run.info = read_seqinfo(sequence_dir / "seqinfo.ini");
  const auto detections = load_detections(sequence_dir / options.detections, run.info);

  tracker::TrackerConfig config = options.config;
  config.frame_rate = run.info.frame_rate;
  config.image_width = static_cast<float>(run.info.width);
  config.image_height = static_cast<float>(run.info.height);
  tracker::Tracker tracker(config);

  using Clock = std::chrono::steady_clock;
  Clock::duration in_update{};
  for (int frame = 1; frame <= run.info.length; frame += options.interval) {
    const double time = (frame - 1) / run.info.frame_rate;
    const auto start = Clock::now();
    const auto& reports = tracker.update(detections[static_cast<std::size_t>(frame - 1)], time);
    in_update += Clock::now() - start;
    for (const auto& report : reports) {
      MotRow row;
      row.frame = frame;
      row.id = report.id;
      row.box = report.box;
      row.conf = report.score;
      run.tracks.push_back(row);
    }
    ++run.frames_processed;
    if (progress) progress(frame, run.info.length);
  }
  run.seconds_in_update = std::chrono::duration<double>(in_update).count();
  return run;
}

}  // namespace rtmot::motio
