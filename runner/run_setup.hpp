#pragma once
// Turns a validated RunConfig into the parts of a Pipeline: source, detector, tracker config, sinks
// and options. Each throws rtmot::InputError naming the config field at fault.
#include <memory>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "messages/frame_result.hpp"
#include "outputs/metrics_server.hpp"
#include "outputs/pipeline_metrics.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/video_source.hpp"
#include "runner/run_config.hpp"

namespace rtmot::runner {

std::unique_ptr<platform::VideoSource> make_source(const RunConfig& config);
std::unique_ptr<detector::Detector> make_detector(const RunConfig& config);
/// What a run sends its tracks to, built from the output section.
struct RunOutputs {
  /// UDP, binary file, MQTT, JSON lines as configured, then the progress line's sink and (with
  /// metrics on) the MetricsSink.
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  /// With output.metrics_port: the numbers (fed by the last sink) and the HTTP endpoint. Keep both
  /// alive longer than the Pipeline that owns the sinks.
  std::unique_ptr<outputs::PipelineMetrics> metrics;
  std::unique_ptr<outputs::MetricsServer> metrics_server;
  /// One line per destination ("udp -> [::1]:5600", "jsonl -> tracks.jsonl (replaces an existing
  /// file)"), for the start-up log.
  std::vector<std::string> destinations;
};
/// `source` gives the progress line its total (a file's frame count).
RunOutputs make_outputs(const RunConfig& config, const platform::SourceInfo& source = {});
/// make_outputs(config).sinks, for runs without metrics.
std::vector<std::unique_ptr<messages::TrackSink>> make_sinks(const RunConfig& config);

/// Before the model loads: checks the annotated video's target (GStreamer has its elements; a
/// file's folders are created and the file can be written). Throws InputError with one clear line.
void prepare_video_output(const RunConfig& config);
/// The configured tracker with what the file left unset (0) taken from the source.
tracker::TrackerConfig complete_tracker_config(const RunConfig& config,
                                               const platform::SourceInfo& source);
pipeline::PipelineOptions make_options(const RunConfig& config);

}  // namespace rtmot::runner
