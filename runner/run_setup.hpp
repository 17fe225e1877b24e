#pragma once
// Turns a validated RunConfig into the parts of a Pipeline: source, detector, tracker config, sinks
// and options. Each throws rtmot::InputError naming the config field at fault.
#include <memory>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "messages/frame_result.hpp"
#include "outputs/live_picture.hpp"
#include "outputs/metrics_server.hpp"
#include "outputs/pipeline_metrics.hpp"
#include "outputs/web_server.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/video_source.hpp"
#include "runner/config_document.hpp"
#include "runner/events_editor.hpp"
#include "runner/run_config.hpp"
#include "runner/settings_editor.hpp"

namespace rtmot::runner {

/// The first (or only) source.
std::unique_ptr<platform::VideoSource> make_source(const RunConfig& config);
/// Every source of source_list(), opened in order (a source that cannot be opened throws its
/// InputError, naming its URI, before anything else is opened), each with its tracker
/// configuration completed from that source and its stream id.
std::vector<pipeline::PipelineInput> make_inputs(const RunConfig& config);
std::unique_ptr<detector::Detector> make_detector(const RunConfig& config);
/// One detector per batch in flight (detector.in_flight; auto: 3 on CUDA, 1 otherwise), built one
/// after another, for the detect stage's lanes; each a TilingDetector around the SSD when
/// detector.tiles asks for tiles, or auto chooses them for the largest of `sources`' frames
/// (runner/tiling_choice.hpp; the choice and its reason are logged).
std::vector<std::unique_ptr<detector::Detector>> make_detectors(
    const RunConfig& config, const std::vector<platform::SourceInfo>& sources);
/// The sources' information, for make_detectors.
std::vector<platform::SourceInfo> source_infos(const std::vector<pipeline::PipelineInput>& inputs);
/// What a run sends its tracks to, built from the output section.
struct RunOutputs {
  /// For the sink stage, in order: UDP, binary file, MQTT, JSON lines as configured, the progress
  /// line (one source), the metrics (with metrics_port), the MOTChallenge results (with
  /// mot_results: runner/mot_results_output.hpp), then the annotated video.
  std::vector<std::unique_ptr<pipeline::FrameConsumer>> consumers;
  /// With output.metrics_port: the numbers (fed by the MetricsSink) and the HTTP endpoint. Keep
  /// both alive longer than the Pipeline that owns the consumers.
  std::unique_ptr<outputs::PipelineMetrics> metrics;
  std::unique_ptr<outputs::EventMetrics> event_metrics;  // with metrics_port and lines or zones
  std::unique_ptr<outputs::MetricsServer> metrics_server;
  /// With output.web_port: each source's live picture, the taps that feed them (with the video's
  /// on the first source), and what the page shows of each source's geometry; the server itself
  /// starts with start_web_server(). Declared in this order so that the server goes first.
  std::vector<std::unique_ptr<outputs::LivePicture>> pictures;
  std::vector<std::unique_ptr<pipeline::TapFanout>> taps;
  /// With output.web_port or a configuration file (SIGHUP re-reads it): what changes while the
  /// run goes on (docs/web.md): the sources' new lines and zones, the detector's score cut, and
  /// the document saves are written to. Declared before the server, which uses them.
  std::vector<std::unique_ptr<pipeline::EventsMailbox>> mailboxes;
  std::unique_ptr<pipeline::EventsMailbox> video_mailbox;  // with output.video_file
  std::unique_ptr<pipeline::ScoreCut> score_cut;
  std::unique_ptr<ConfigDocument> document;
  std::unique_ptr<EventsEditor> events_editor;
  std::unique_ptr<SettingsEditor> settings_editor;
  nlohmann::json web_sources;
  std::unique_ptr<outputs::WebServer> web_server;
  /// One line per destination ("udp -> [::1]:5600", "jsonl -> tracks.jsonl (replaces an existing
  /// file)"), for the start-up log.
  std::vector<std::string> destinations;
  /// The network outputs' counters, read at the end for the final report (valid while the
  /// Pipeline that owns the consumers lives).
  std::vector<outputs::OutputProbe> deliveries;
};
/// `inputs` (opened) give the progress line its total (a file's frame count) and the video its
/// rate; the video sets the first input's tap (every source frame reaches it).
RunOutputs make_outputs(const RunConfig& config, std::vector<pipeline::PipelineInput>& inputs);
/// With output.web_port: the operator's page (outputs/web_server.hpp), listening at once;
/// `detector` is the detector's description it shows. Call after make_outputs, before the run.
/// Throws InputError if it cannot listen or its files are missing.
void start_web_server(const RunConfig& config, RunOutputs& outputs, const std::string& detector);
/// Only the message sinks (UDP, binary, MQTT, JSON lines), for runs without video or metrics.
std::vector<std::unique_ptr<messages::TrackSink>> make_sinks(const RunConfig& config);

/// Before anything is opened for writing and the model loads: checks that no output file names an
/// input or another output (common/distinct_files.hpp), and the annotated video's target
/// (GStreamer has its elements and the encoder takes the source's size; a file's folders are
/// created and the file can be written). Throws InputError with one clear line.
void prepare_video_output(const RunConfig& config);
/// The configured tracker with what the file left unset (0) taken from the source.
tracker::TrackerConfig complete_tracker_config(const RunConfig& config,
                                               const platform::SourceInfo& source);
pipeline::PipelineOptions make_options(const RunConfig& config);

}  // namespace rtmot::runner
