#include "runner/run_setup.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <opencv2/core/utility.hpp>

#include "common/input_error.hpp"
#include "detector/dnn_backend.hpp"
#include "detector/replay_detector.hpp"
#include "detector/ssd_detector.hpp"
#include "messages/binary_file_sink.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/udp_sink.hpp"
#include "motio/mot_files.hpp"
#include "runner/host_port.hpp"
#include "runner/source_factory.hpp"
#include "tracker/score_scale.hpp"

namespace rtmot::runner {
namespace {

std::unique_ptr<platform::VideoSource> open_configured(const SourceConfig& source) {
  platform::SourceOptions options;
  options.width = source.width;
  options.height = source.height;
  options.fps = source.fps;
  return open_source(source.uri, options);
}

}  // namespace

std::unique_ptr<platform::VideoSource> make_source(const RunConfig& config) {
  return open_configured(source_list(config).front());
}

std::vector<pipeline::PipelineInput> make_inputs(const RunConfig& config) {
  const std::vector<SourceConfig> sources = source_list(config);
  std::vector<pipeline::PipelineInput> inputs(sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    inputs[i].source = open_configured(sources[i]);
    inputs[i].tracker = complete_tracker_config(config, inputs[i].source->info());
    inputs[i].stream_id = stream_id_of(config, i);
  }
  return inputs;
}

namespace {

// A replayed detections file is cut twice on absolute scores: by the detector's score_threshold
// and by the tracker's own cuts. Both assume [0, 1] scores; a file on another scale gets one
// warning naming it and the range seen (tracker/score_scale.hpp). The SSD's scores are its own
// sigmoid in [0, 1], where its threshold was chosen, so it needs none.
void warn_on_score_scale(const DetectorConfig& detector, const tracker::TrackerConfig& tracker) {
  tracker::ScoreRange range;
  for (const auto& row : motio::read_mot_file(detector.det_file, motio::MotFileKind::detections))
    range.include(row.conf);
  tracker::TrackerConfig cuts = tracker;
  cuts.detection_threshold = std::max(cuts.detection_threshold, detector.score_threshold);
  if (const auto warning = tracker::score_scale_warning(cuts, range))
    spdlog::warn("{}: {} (detector.score_threshold {})", detector.det_file, *warning,
                 detector.score_threshold);
}

}  // namespace

std::unique_ptr<detector::Detector> make_detector(const RunConfig& config) {
  const DetectorConfig& wanted = config.detector;
  if (wanted.kind == "replay") {
    auto replay =
        std::make_unique<detector::ReplayDetector>(wanted.det_file, wanted.score_threshold);
    warn_on_score_scale(wanted, config.tracker);
    return replay;
  }
  detector::SsdConfig ssd;
  ssd.model_path = wanted.model;
  ssd.anchors_path = wanted.anchors;
  ssd.score_threshold = wanted.score_threshold;
  ssd.nms_iou = wanted.nms_threshold;
  ssd.classes = wanted.classes;
  // Both were checked by the config parser.
  ssd.backend = detector::parse_backend_request(wanted.backend).value();
  ssd.fp16 = detector::parse_fp16_request(wanted.fp16).value();
  // 0 ("automatic") is made explicit. Left to itself, a TBB build of OpenCV (Debian's, ours) runs
  // its DNN in TBB's automatic arena, sized by TBB: it ignores OpenCV's own OPENCV_FOR_THREADS_NUM
  // (measured) and, depending on the TBB version, a container's CPU quota (docker --cpus), so it
  // can run more workers than the CPUs we may use, and a layer split over them waits for its
  // slowest part. OpenCV's CPU count honours the affinity mask, cpusets and the cgroup quota; on a
  // machine without either both give the same count (measured: no difference on the 2-core CI
  // machine).
  ssd.threads = wanted.threads > 0 ? wanted.threads : std::max(1, cv::getNumberOfCPUs());
  spdlog::info("detector threads: {}{}", ssd.threads,
               wanted.threads > 0 ? "" : " (the CPUs this process may use)");
  // One forward pass takes one frame of every source (the detect stage batches them): without
  // this the SSD would split each batch into single images again.
  ssd.max_batch = static_cast<int>(
      std::clamp<std::size_t>(source_list(config).size(), 1, detector::kMaxBatchLimit));
  return std::make_unique<detector::SsdDetector>(ssd);
}

std::vector<std::unique_ptr<messages::TrackSink>> make_sinks(const RunConfig& config) {
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  const OutputConfig& output = config.output;
  if (!output.udp.empty()) {
    // Checked when the file was read (with its line) or the override given.
    const HostPort target =
        parse_host_port(output.udp, config.file, 0, "output.udp", ExitCode::bad_input);
    sinks.push_back(std::make_unique<messages::UdpSink>(target.host, target.port));
  }
  if (!output.binary_file.empty()) {
    sinks.push_back(std::make_unique<messages::BinaryFileSink>(output.binary_file));
  }
  if (!output.jsonl_file.empty())
    sinks.push_back(std::make_unique<messages::JsonlSink>(output.jsonl_file));
  return sinks;
}

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
  options.stats_interval_s = config.stats_interval_s;
  options.video_file = config.output.video_file;
  options.threads = config.threads;
  return options;
}

}  // namespace rtmot::runner
