// run_setup.hpp's options: the tracker's configuration completed from a source, and the pipeline's.
#include "runner/run_setup.hpp"

namespace rtmot::runner {

tracker::TrackerConfig complete_tracker_config(const RunConfig& config,
                                               const platform::SourceInfo& source) {
  tracker::TrackerConfig tracker = config.tracker;
  if (tracker.frame_rate <= 0.0) tracker.frame_rate = source.fps > 0.0 ? source.fps : 30.0;
  if (tracker.image_width <= 0.F) {
    tracker.image_width = source.width > 0 ? static_cast<float>(source.width) : 1920.F;
  }
  if (tracker.image_height <= 0.F) {
    tracker.image_height = source.height > 0 ? static_cast<float>(source.height) : 1080.F;
  }
  return tracker;
}

pipeline::PipelineOptions make_options(const RunConfig& config) {
  pipeline::PipelineOptions options;
  options.playback = config.playback.mode;
  options.simulated_latency_ms = config.playback.latency_ms;
  options.stream_id = config.stream_id;
  options.max_frames = config.max_frames;
  options.stats_interval_s = config.stats_interval_s;  // the sink stage's periodic line
  // The annotated video takes its pictures through the source's tap (make_outputs), not through
  // the queues.
  options.keep_images = false;
  options.full_rate = config.output.full_rate;
  options.keep_detections = config.output.mot_detections;
  options.follow_image = config.detector.follow_image;
  options.threads = config.threads;
  return options;
}

}  // namespace rtmot::runner
