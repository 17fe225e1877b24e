#include "runner/run_setup.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "common/input_error.hpp"
#include "detector/coco_labels.hpp"
#include "detector/dnn_backend.hpp"
#include "detector/replay_detector.hpp"
#include "detector/ssd_detector.hpp"
#include "messages/binary_file_sink.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/udp_sink.hpp"
#include "outputs/mqtt_publisher.hpp"
#include "outputs/video_stream.hpp"
#include "outputs/video_target.hpp"
#include "platform/host_port.hpp"
#include "runner/progress_sink.hpp"
#include "runner/source_factory.hpp"

namespace rtmot::runner {
namespace {

platform::HostPort parse_udp_target(const RunConfig& config) {
  std::string problem;
  const auto target = platform::parse_host_port(config.output.udp, problem);
  if (!target) {
    throw InputError(
        config.file, 0, "output.udp",
        "expected HOST:PORT or [IPV6]:PORT, got '" + config.output.udp + "': " + problem);
  }
  return *target;
}

}  // namespace

std::unique_ptr<platform::VideoSource> make_source(const RunConfig& config) {
  platform::SourceOptions options;
  options.width = config.source.width;
  options.height = config.source.height;
  options.fps = config.source.fps;
  return open_source(config.source.uri, options);
}

std::unique_ptr<detector::Detector> make_detector(const RunConfig& config) {
  const DetectorConfig& wanted = config.detector;
  if (wanted.kind == "replay") {
    return std::make_unique<detector::ReplayDetector>(wanted.det_file, wanted.score_threshold);
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
  ssd.threads = wanted.threads;
  return std::make_unique<detector::SsdDetector>(ssd);
}

RunOutputs make_outputs(const RunConfig& config, const platform::SourceInfo& source) {
  RunOutputs outputs;
  std::vector<outputs::OutputProbe> probes;
  const OutputConfig& output = config.output;
  // Files: missing folders are created (out/tracks.jsonl on a fresh clone), and the log says when
  // an existing file is replaced.
  const auto file_line = [](const char* kind, const std::string& path) {
    std::error_code error;
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent, error);
    return fmt::format("{} -> {}{}", kind, path,
                       std::filesystem::exists(path, error) ? " (replaces the existing file)" : "");
  };
  if (!output.udp.empty()) {
    const platform::HostPort target = parse_udp_target(config);
    auto sink = std::make_unique<messages::UdpSink>(target.host, target.port);
    const messages::UdpSink* udp = sink.get();
    probes.push_back(
        {"udp", [udp] { return udp->messages_sent(); }, [udp] { return udp->send_failures(); }});
    outputs.destinations.push_back("udp -> " +
                                   platform::format_host_port(target.host, target.port));
    outputs.sinks.push_back(std::move(sink));
  }
  if (!output.binary_file.empty()) {
    outputs.destinations.push_back(file_line("binary", output.binary_file));
    outputs.sinks.push_back(std::make_unique<messages::BinaryFileSink>(output.binary_file));
  }
  if (!output.mqtt.empty()) {
    std::string problem;  // checked by validate()
    outputs::MqttPublisherOptions mqtt;
    mqtt.uri = outputs::parse_mqtt_uri(output.mqtt, problem).value();
    auto sink =
        std::make_unique<outputs::MqttPublisher>(mqtt, config.stream_id, &detector::coco_label);
    const outputs::MqttPublisher* publisher = sink.get();
    probes.push_back({"mqtt", [publisher] { return publisher->counters().published.load(); },
                      [publisher] {
                        return publisher->counters().dropped.load() +
                               publisher->counters().failed.load();
                      }});
    outputs.destinations.push_back("mqtt -> " + outputs::to_string(mqtt.uri));
    outputs.sinks.push_back(std::move(sink));
  }
  if (!output.jsonl_file.empty()) {
    outputs.destinations.push_back(file_line("jsonl", output.jsonl_file));
    outputs.sinks.push_back(
        std::make_unique<messages::JsonlSink>(output.jsonl_file, &detector::coco_label));
  }
  if (!output.video_file.empty()) {
    outputs.destinations.push_back("video -> " + output.video_file + " (overlay " + output.overlay +
                                   ")");
  }
  if (!output.report_file.empty()) {
    outputs.destinations.push_back(file_line("report", output.report_file));
  }
  if (config.stats_interval_s > 0.0) {
    outputs.sinks.push_back(
        std::make_unique<ProgressSink>(config.stats_interval_s, source.frame_count));
  }
  if (output.metrics_port > 0) {
    outputs.metrics = std::make_unique<outputs::PipelineMetrics>(std::move(probes));
    outputs.metrics_server = std::make_unique<outputs::MetricsServer>(
        *outputs.metrics, output.metrics_bind, static_cast<std::uint16_t>(output.metrics_port));
    outputs.sinks.push_back(std::make_unique<outputs::MetricsSink>(*outputs.metrics));
    outputs.destinations.push_back("metrics -> " + outputs.metrics_server->url());
  }
  return outputs;
}

std::vector<std::unique_ptr<messages::TrackSink>> make_sinks(const RunConfig& config) {
  return std::move(make_outputs(config).sinks);
}

void prepare_video_output(const RunConfig& config) {
  if (config.output.video_file.empty()) return;
  std::string problem;
  const auto target = outputs::parse_video_target(config.output.video_file, problem);
  const auto fail = [&](const std::string& why) {
    throw InputError(config.output.video_file, 0, "output.video_file", why);
  };
  if (!target) fail(problem);
  problem = outputs::check_video_elements(*target);
  if (!problem.empty()) fail(problem);
  if (target->kind == outputs::VideoTargetKind::mp4_file ||
      target->kind == outputs::VideoTargetKind::mkv_file) {
    problem = outputs::prepare_video_file(*target);
    if (!problem.empty()) fail("cannot write the video: " + problem);
  }
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
  // The progress line is ProgressSink's (make_outputs), with the total and ETA the engine's own
  // line cannot know.
  options.stats_interval_s = 0.0;
  options.video_file = config.output.video_file;
  return options;
}

}  // namespace rtmot::runner
