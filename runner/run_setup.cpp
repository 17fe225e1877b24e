#include "runner/run_setup.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <opencv2/core/utility.hpp>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/utf8.hpp"
#include "detector/dnn_backend.hpp"
#include "detector/model_checksum.hpp"
#include "detector/replay_detector.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/tiling_detector.hpp"
#include "messages/binary_file_sink.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/udp_sink.hpp"
#include "motio/mot_files.hpp"
#include "outputs/annotated_video.hpp"
#include "outputs/mqtt_publisher.hpp"
#include "outputs/overlay.hpp"
#include "outputs/video_encoding.hpp"
#include "outputs/video_stream.hpp"
#include "outputs/video_target.hpp"
#include "platform/host_port.hpp"
#include "platform/log_setup.hpp"
#include "platform/looping_source.hpp"
#include "platform/oriented_source.hpp"
#include "platform/video_uri.hpp"
#include "runner/class_choice.hpp"
#include "runner/mot_results_output.hpp"
#include "runner/run_files.hpp"
#include "runner/sequence_clock_source.hpp"
#include "runner/source_factory.hpp"
#include "runner/tiling_choice.hpp"
#include "runner/web_geometry.hpp"
#include "tracker/score_scale.hpp"
#include "vision/appearance_detector.hpp"

namespace rtmot::runner {
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

namespace {

// `first`: the first of a run's detectors logs and warns; the lanes after it are alike.
// `images_per_pass`: the images one forward pass takes (the sources, times a frame's tiles).
std::unique_ptr<detector::Detector> build_detector(const RunConfig& config, bool first,
                                                   int images_per_pass) {
  const DetectorConfig& wanted = config.detector;
  if (wanted.kind == DetectorKind::replay) {
    auto replay =
        std::make_unique<detector::ReplayDetector>(wanted.det_file, wanted.score_threshold);
    if (first) warn_on_score_scale(wanted, config.tracker);
    return replay;
  }
  detector::SsdConfig ssd;
  ssd.model_path = wanted.model;
  ssd.anchors_path = wanted.anchors;
  ssd.int8_ranges = wanted.int8_ranges;
  ssd.score_threshold = wanted.score_threshold;
  ssd.nms_iou = wanted.nms_threshold;
  ssd.classes = resolve_classes(config, *run_labels(config));
  ssd.backend = wanted.backend;
  ssd.fp16 = wanted.fp16;
  ssd.plausible_shapes = wanted.plausible_shapes;
  // 0 ("automatic") is made explicit. Left to itself, a TBB build of OpenCV (Debian's, ours) runs
  // its DNN in TBB's automatic arena, sized by TBB: it ignores OpenCV's own OPENCV_FOR_THREADS_NUM
  // (measured) and, depending on the TBB version, a container's CPU quota (docker --cpus), so it
  // can run more workers than the CPUs we may use, and a layer split over them waits for its
  // slowest part. OpenCV's CPU count honours the affinity mask, cpusets and the cgroup quota; on a
  // machine without either both give the same count (measured: no difference on the 2-core CI
  // machine).
  // This is the one place that decides detector.threads, and the setting is process-wide
  // (cv::setNumThreads): made here, in the open. The detector gets the number decided, not 0:
  // its XNNPACK pool and backend auto's choice are sized by it (issue 32: handed 0, auto never
  // saw one thread).
  const int threads = wanted.threads > 0 ? wanted.threads : std::max(1, cv::getNumberOfCPUs());
  cv::setNumThreads(threads);
  ssd.threads = threads;
  if (first) {
    spdlog::info("detector threads: {}{}", threads,
                 wanted.threads > 0 ? "" : " (the CPUs this process may use)");
  }
  // One forward pass takes one frame of every source (the detect stage batches them), and with
  // tiles every tile of those frames: without this the SSD would split each batch again.
  ssd.max_batch = std::clamp(images_per_pass, 1, detector::kMaxBatchLimit);
  return std::make_unique<detector::SsdDetector>(ssd);
}

int source_count(const RunConfig& config) {
  return static_cast<int>(
      std::clamp<std::size_t>(source_list(config).size(), 1, detector::kMaxBatchLimit));
}

// The largest frame of the run's sources (by area), with its rate.
FrameShape largest_frame(const std::vector<platform::SourceInfo>& sources) {
  FrameShape frame;
  for (const platform::SourceInfo& info : sources) {
    if (static_cast<long long>(info.width) * info.height >
        static_cast<long long>(frame.width) * frame.height) {
      frame = {info.width, info.height, info.fps, info.live};
    }
  }
  for (const platform::SourceInfo& info : sources) frame.live = frame.live || info.live;
  return frame;
}

// The milliseconds of the middle of three calls (after one to warm up).
template <typename Call>
double median_ms(Call call) {
  std::vector<double> ms;
  call();
  for (int i = 0; i < 3; ++i) {
    const auto start = std::chrono::steady_clock::now();
    call();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[1];
}

// A grey frame of this shape, cut into its passes (the network's work does not depend on the
// pixels), and what a detector takes for the first `count` of them in one batch.
class CostProbe {
 public:
  CostProbe(const FrameShape& frame, const std::vector<detector::PixelRect>& passes)
      : grey_(frame.height, frame.width, CV_8UC3, cv::Scalar::all(114)) {
    for (const detector::PixelRect& r : passes)
      views_.push_back(grey_(cv::Rect(r.x, r.y, r.width, r.height)));
    for (const cv::Mat& view : views_) images_.push_back(&view);
    numbers_.assign(images_.size(), 1);
  }
  double batch_ms(detector::Detector& ssd, std::size_t count) {
    return median_ms(
        [&] { ssd.detect_batch(images_.data(), numbers_.data(), static_cast<int>(count), out_); });
  }
  std::size_t passes() const { return images_.size(); }

 private:
  cv::Mat grey_;
  std::vector<cv::Mat> views_;
  std::vector<const cv::Mat*> images_;
  std::vector<std::int64_t> numbers_;
  std::vector<std::vector<tracker::Detection>> out_;
};

// The image's work is done only where the tracker will use it.
bool measures_appearance(const RunConfig& config) {
  const tracker::TrackerConfig& tracker = config.tracker;
  return config.detector.appearance && (tracker.appearance_weight > 0.0 ||
                                        tracker.appearance_gate < 1.0 || tracker.reid_gate > 0.0);
}

bool runs_on_cpu(const detector::Detector& detector) {
  const auto* ssd = dynamic_cast<const detector::SsdDetector*>(&detector);
  return ssd != nullptr && ssd->backend().backend != cv::dnn::DNN_BACKEND_CUDA;
}

}  // namespace

std::unique_ptr<detector::Detector> make_detector(const RunConfig& config) {
  auto built = build_detector(config, true, source_count(config));
  if (measures_appearance(config))
    built = std::make_unique<vision::AppearanceDetector>(std::move(built));
  return built;
}

std::vector<platform::SourceInfo> source_infos(const std::vector<pipeline::PipelineInput>& inputs) {
  std::vector<platform::SourceInfo> infos;
  for (const auto& input : inputs) infos.push_back(input.source->info());
  return infos;
}

std::vector<std::unique_ptr<detector::Detector>> make_detectors(
    const RunConfig& config, const std::vector<platform::SourceInfo>& sources) {
  const DetectorConfig& wanted = config.detector;
  const FrameShape frame = largest_frame(sources);
  const detector::TilingConfig tiling = tiling_config(wanted);
  // The passes of the largest frame if it is tiled: the SSD's batch is sized for them.
  const std::size_t tiled_passes =
      wanted.kind == DetectorKind::ssd && wanted.tiles.mode != detector::TileMode::off &&
              frame.width > 0 && frame.height > 0
          ? detector::TilingDetector::plan_passes(frame.width, frame.height, tiling).size()
          : 1;
  const int sources_per_pass = source_count(config);
  std::vector<std::unique_ptr<detector::Detector>> lanes;
  std::optional<DetectorCost> cost;
  if (tiled_passes > 1 && tiling_needs_measurement(wanted, config.playback.mode, frame)) {
    // Timed in two steps: the whole frame on a detector sized for it, then the tiled batch only
    // where the whole frame's cost leaves room for it (on the CPU it mostly does not, and building
    // and timing the batch took 2-3 s of start-up).
    lanes.push_back(build_detector(config, true, sources_per_pass));
    CostProbe probe(frame,
                    detector::TilingDetector::plan_passes(frame.width, frame.height, tiling));
    cost = DetectorCost{probe.batch_ms(*lanes.front(), 1), 0.0, false};
    if (tiled_cost_needs_timing(frame, cost->whole_ms, probe.passes(),
                                runs_on_cpu(*lanes.front()))) {
      lanes.front() =
          build_detector(config, false, sources_per_pass * static_cast<int>(tiled_passes));
      cost->tiled_ms = probe.batch_ms(*lanes.front(), probe.passes());
    } else {
      cost->tiled_ms = cpu_tiled_floor_ms(cost->whole_ms, probe.passes());
      cost->tiled_estimated = true;
    }
  } else {
    lanes.push_back(
        build_detector(config, true, sources_per_pass * static_cast<int>(tiled_passes)));
  }
  const TilingDecision decision = decide_tiling(wanted, config.playback.mode, frame, cost);
  const bool tiled = decision.tiled && tiled_passes > 1;
  spdlog::info("{}", decision.why);
  if (!tiled && tiled_passes > 1 && !(cost && cost->tiled_estimated)) {
    // Sized for tiles that will not be cut: its batch network would compute empty slots.
    lanes.front() = build_detector(config, false, sources_per_pass);
  }
  const auto lane_images = sources_per_pass * (tiled ? static_cast<int>(tiled_passes) : 1);
  const auto* ssd = dynamic_cast<const detector::SsdDetector*>(lanes.front().get());
  const bool cuda = ssd != nullptr && ssd->backend().backend == cv::dnn::DNN_BACKEND_CUDA;
  // auto: on CUDA the GPU runs one batch while the host prepares and decodes the others. Measured
  // on an H200, 8 sources, every frame, two passes (docs/gpu.md §3, "Batches in flight", the
  // batch's images preprocessed in parallel): 1 -> 2 -> 3 -> 4 lanes gave 1311-1567 -> 1890-2215
  // -> 1969-2464 -> 2357-2735 FPS on cuda, p99 12-16 -> 17-20 -> 19-24 -> 20-25 ms: 3 keeps p99
  // within what one lane had before the parallel preprocessing (24-25 ms). On cuda-fp16 the GPU
  // is the limit sooner: 840-934 -> 1193-1196 -> 1292-1301 -> 1390 FPS, GPU busy 53-59 -> 69-71
  // -> 74 -> 77-79 %, and p99 20-23 -> 29 -> 37 -> 45-46 ms: 2 lanes keep p99 within one lane's
  // before (28-32 ms) and stay above 900 FPS; a 3rd buys 8 % for 30 % more p99. At a camera rate
  // (8 x 60 fps) the lane count does not move p99 (8-13 ms). On the H100 (docs/gpu.md, "Three
  // lanes on cuda-fp16") 2 lanes left the GPU busy 65-69 % at 8 sources and 3 reached 71-72 %
  // (the 70 %) with 1235-1262 FPS and p99 37.6-38.4 ms, within what one lane had before
  // batches in flight (37.6-44.9 ms), and camera-rate p99 the same (12.7 against 12.2 ms): so 3
  // on fp16 as on fp32. Each lane holds its own networks and host thread. One on the CPU, where a
  // second lane only takes cores from the first's OpenCV threads (docs/gpu.md).
  const int automatic = cuda ? 3 : 1;
  const int in_flight = wanted.in_flight > 0 ? wanted.in_flight : automatic;
  // One after another: each loads, warms up and (CUDA) captures its graphs alone.
  while (static_cast<int>(lanes.size()) < in_flight) {
    lanes.push_back(build_detector(config, false, lane_images));
  }
  spdlog::info("detector: {} batch{} in flight{}", in_flight, in_flight == 1 ? "" : "es",
               config.detector.in_flight > 0 ? ""
               : cuda                        ? " (auto: CUDA)"
                                             : " (auto: not CUDA)");
  if (tiled) {
    for (auto& lane : lanes) {
      lane = std::make_unique<detector::TilingDetector>(std::move(lane), tiling);
    }
  }
  if (measures_appearance(config)) {
    for (auto& lane : lanes) lane = std::make_unique<vision::AppearanceDetector>(std::move(lane));
  }
  return lanes;
}

RunOutputs make_outputs(const RunConfig& config, std::vector<pipeline::PipelineInput>& inputs) {
  // The one place a run's outputs are opened (run, soak): none may name an input or another
  // output. `run` checked already in prepare_video_output (before its video's temporary); soak
  // comes here only.
  check_run_files(config);
  RunOutputs outputs;
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  // The model's own class names in every output that names classes; each holds the table.
  const auto labels = run_labels(config);
  const messages::ClassLabelFn label_of = [labels](int id) { return labels->name(id); };
  const platform::SourceInfo first =
      inputs.empty() ? platform::SourceInfo{} : inputs.front().source->info();
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
  // First: the results folder is created here, and one that cannot be fails before any other
  // output is opened.
  std::unique_ptr<pipeline::FrameConsumer> mot_results;
  if (!output.mot_results.empty()) {
    const std::vector<MotResultsTarget> targets = mot_results_targets(config);
    mot_results =
        std::make_unique<MotResultsOutput>(output.mot_results, targets, output.mot_detections);
    for (const auto& target : targets) {
      outputs.destinations.push_back(
          file_line("mot results", mot_results_file(output.mot_results, target.name).string()) +
          " and " + target.name + ".frames" +
          (output.mot_detections ? " and " + target.name + ".det.txt" : ""));
    }
  }
  if (output.udp) {
    const HostPort& target = *output.udp;
    auto sink = std::make_unique<messages::UdpSink>(target.host, target.port);
    const messages::UdpSink* udp = sink.get();
    probes.push_back({"udp",
                      [udp] { return udp->messages_sent(); },
                      [udp] { return udp->send_failures(); },
                      {},
                      {}});
    outputs.destinations.push_back("udp -> " +
                                   platform::format_host_port(target.host, target.port));
    sinks.push_back(std::move(sink));
  }
  if (!output.binary_file.empty()) {
    outputs.destinations.push_back(file_line("binary", output.binary_file));
    sinks.push_back(std::make_unique<messages::BinaryFileSink>(output.binary_file));
  }
  if (output.mqtt) {
    outputs::MqttPublisherOptions mqtt;
    mqtt.uri = *output.mqtt;
    auto sink = std::make_unique<outputs::MqttPublisher>(mqtt, config.stream_id, label_of);
    const outputs::MqttPublisher* publisher = sink.get();
    probes.push_back(
        {"mqtt", [publisher] { return publisher->counters().published.load(); },
         [publisher] {
           return publisher->counters().dropped.load() + publisher->counters().failed.load();
         },
         [publisher] {
           return publisher->counters().queued.load() + publisher->counters().dropped.load();
         },
         [publisher, uri = outputs::to_string(mqtt.uri)] {
           return publisher->counters().connects.load() == 0
                      ? "the broker (" + uri + ") was never reached"
                      : std::string();
         }});
    outputs.destinations.push_back("mqtt -> " + outputs::to_string(mqtt.uri));
    sinks.push_back(std::move(sink));
  }
  if (!output.jsonl_file.empty()) {
    outputs.destinations.push_back(file_line("jsonl", output.jsonl_file));
    sinks.push_back(std::make_unique<messages::JsonlSink>(output.jsonl_file, label_of));
  }
  std::unique_ptr<pipeline::FrameConsumer> video;
  outputs::AnnotatedVideo* annotated_video = nullptr;
  if (output.video) {
    auto annotated = std::make_unique<outputs::AnnotatedVideo>(*output.video, output.video_encoding,
                                                               first, output.overlay, label_of);
    // One source (validate() checked it): the video sees every one of its frames.
    if (!inputs.empty()) inputs.front().tap = annotated->tap();
    const auto& counted = inputs.empty() ? events::EventsConfig{} : inputs.front().events;
    if (!counted.lines.empty() || !counted.zones.empty()) annotated->show_events(counted);
    annotated_video = annotated.get();
    video = std::move(annotated);
    outputs.destinations.push_back(
        "video -> " + output.video->text +
        (output.video->kind == outputs::VideoTargetKind::display
             ? std::string(" (a window)")
             : " (" + std::string(outputs::codec_title(output.video_encoding.codec)) + ")"));
  }
  if (!output.report_file.empty()) {
    outputs.destinations.push_back(file_line("report", output.report_file));
  }
  outputs.deliveries = probes;  // for the final report
  // What a save on the page or a SIGHUP changes while the run goes on.
  const bool live = !inputs.empty() && (output.web_port > 0 || !config.loaded_from.empty());
  std::vector<EventsEditor::Source> editable;
  if (live) {
    for (auto& input : inputs) {
      outputs.mailboxes.push_back(std::make_unique<pipeline::EventsMailbox>());
      input.events_mailbox = outputs.mailboxes.back().get();
      const platform::SourceInfo& info = input.source->info();
      editable.push_back({input.stream_id, info.uri, static_cast<int>(input.tracker.image_width),
                          static_cast<int>(input.tracker.image_height), input.events,
                          input.events_mailbox, nullptr});
    }
    if (annotated_video != nullptr) {
      // One source (validate() checked it): the video draws its lines as they change.
      outputs.video_mailbox = std::make_unique<pipeline::EventsMailbox>();
      annotated_video->follow_events(outputs.video_mailbox.get());
      editable.front().video_mailbox = outputs.video_mailbox.get();
    }
    outputs.score_cut = std::make_unique<pipeline::ScoreCut>(config.detector.score_threshold);
    outputs.document = std::make_unique<ConfigDocument>(config.loaded_from, output.web_save_to);
    outputs.settings_editor =
        std::make_unique<SettingsEditor>(*outputs.score_cut, *outputs.document);
  }
  if (output.web_port > 0) {
    std::vector<outputs::LivePicture*> pictures;
    outputs.web_sources = nlohmann::json::array();
    // The live picture shows the tracks; the page draws the lines and zones itself (and the
    // frame rate and latency from the status), so that a line drawn shows at once.
    outputs::OverlayFlags flags = output.overlay;
    flags.bits &= ~static_cast<unsigned>(outputs::OverlayFlag::stats);
    for (auto& input : inputs) {
      auto picture = std::make_unique<outputs::LivePicture>(input.stream_id, flags, label_of);
      if (input.tap != nullptr) {
        outputs.taps.push_back(std::make_unique<pipeline::TapFanout>(
            std::vector<pipeline::FrameTap*>{input.tap, picture.get()}));
        input.tap = outputs.taps.back().get();
      } else {
        input.tap = picture.get();
      }
      pictures.push_back(picture.get());
      outputs.pictures.push_back(std::move(picture));
      const platform::SourceInfo& info = input.source->info();
      outputs.web_sources.push_back(
          web_geometry(input.events, input.stream_id, info.uri, info.width, info.height));
    }
    sinks.push_back(std::make_unique<outputs::LivePictureSink>(std::move(pictures)));
  }
  if (output.metrics_port > 0 || output.web_port > 0) {
    std::vector<std::uint32_t> streams;
    for (const auto& input : inputs) streams.push_back(input.stream_id);
    outputs.metrics = std::make_unique<outputs::PipelineMetrics>(std::move(probes), streams);
    std::vector<outputs::EventMetrics::Source> counted;
    for (const auto& input : inputs) {
      // With the page or a file to re-read every source is counted: its lines may be drawn or
      // added while it runs.
      if (input.events.lines.empty() && input.events.zones.empty() && !live) continue;
      outputs::EventMetrics::Source source{input.stream_id, {}, {}};
      for (const auto& line : input.events.lines) source.lines.push_back(line.name);
      for (const auto& zone : input.events.zones) source.zones.push_back(zone.name);
      counted.push_back(std::move(source));
    }
    if (!counted.empty()) {
      outputs.event_metrics =
          std::make_unique<outputs::EventMetrics>(std::move(counted), labels->columns(), label_of);
      outputs.metrics->set_event_metrics(outputs.event_metrics.get());
      sinks.push_back(std::make_unique<outputs::EventMetricsSink>(*outputs.event_metrics));
    }
    if (output.metrics_port > 0) {
      outputs.metrics_server = std::make_unique<outputs::MetricsServer>(
          *outputs.metrics, output.metrics_bind, static_cast<std::uint16_t>(output.metrics_port));
      outputs.destinations.push_back("metrics -> " + outputs.metrics_server->url());
    }
    sinks.push_back(std::make_unique<outputs::MetricsSink>(*outputs.metrics));
  }
  if (live) {
    outputs.events_editor =
        std::make_unique<EventsEditor>(std::move(editable), outputs.event_metrics.get(),
                                       *outputs.document, !config.sources.empty());
  }
  outputs.consumers = pipeline::as_consumers(std::move(sinks));
  if (mot_results) outputs.consumers.push_back(std::move(mot_results));
  // The video last: it draws on the picture, after every message went out.
  if (video) outputs.consumers.push_back(std::move(video));
  return outputs;
}

void start_web_server(const RunConfig& config, RunOutputs& outputs, const std::string& detector) {
  if (config.output.web_port <= 0) return;
  outputs::WebContent content;
  content.metrics = outputs.metrics.get();
  for (const auto& picture : outputs.pictures) content.pictures.push_back(picture.get());
  content.sources = outputs.web_sources;
  content.detector = detector;
  if (!config.output.web_token_file.empty()) {
    std::string token = read_text_file(config.output.web_token_file);
    while (!token.empty() && std::isspace(static_cast<unsigned char>(token.back())))
      token.pop_back();
    if (token.size() < 16) {
      throw InputError(config.output.web_token_file, 0, "output.web_token_file",
                       "a token of at least 16 characters is needed (e.g. openssl rand -hex 16)");
    }
    content.token = std::move(token);
    content.save_events = [editor = outputs.events_editor.get()](std::size_t source,
                                                                 const std::string& body) {
      return editor->save(source, body);
    };
    content.save_settings = [editor = outputs.settings_editor.get()](const std::string& body) {
      return editor->save(body);
    };
  }
  content.settings = [editor = outputs.settings_editor.get()] { return editor->current(); };
  content.geometry = [editor = outputs.events_editor.get()] { return editor->geometry(); };
  outputs.web_server = std::make_unique<outputs::WebServer>(
      std::move(content), config.output.web_bind,
      static_cast<std::uint16_t>(config.output.web_port), outputs::find_static_dir());
}

std::vector<std::unique_ptr<messages::TrackSink>> make_sinks(const RunConfig& config) {
  RunConfig messages_only = config;
  messages_only.output.video.reset();
  messages_only.output.metrics_port = 0;
  messages_only.output.web_port = 0;
  messages_only.output.mot_results.clear();
  messages_only.stats_interval_s = 0.0;
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  // make_outputs' consumers are the message sinks in order; unwrap them.
  std::vector<pipeline::PipelineInput> no_inputs;
  for (auto& consumer : make_outputs(messages_only, no_inputs).consumers) {
    sinks.push_back(static_cast<pipeline::TrackSinkConsumer&>(*consumer).release());
  }
  return sinks;
}

}  // namespace rtmot::runner
