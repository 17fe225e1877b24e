// run_setup.hpp's outputs: the message sinks, MOTChallenge results, annotated video, metrics and
// the operator's page a run sends its tracks to.
#include <fmt/format.h>

#include <cctype>
#include <filesystem>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "messages/binary_file_sink.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/udp_sink.hpp"
#include "outputs/annotated_video.hpp"
#include "outputs/mqtt_publisher.hpp"
#include "outputs/overlay.hpp"
#include "outputs/video_encoding.hpp"
#include "outputs/video_target.hpp"
#include "platform/host_port.hpp"
#include "runner/class_choice.hpp"
#include "runner/mot_results_output.hpp"
#include "runner/run_files.hpp"
#include "runner/run_setup.hpp"
#include "runner/web_geometry.hpp"

namespace rtmot::runner {

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
