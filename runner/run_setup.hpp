#pragma once
// Turns a validated RunConfig into the parts of a Pipeline: source, detector, tracker config, sinks
// and options. Each throws rtmot::InputError naming the config field at fault.
#include <memory>
#include <vector>

#include "detector/detector.hpp"
#include "messages/frame_result.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/video_source.hpp"
#include "runner/run_config.hpp"

namespace rtmot::runner {

/// The first (or only) source.
std::unique_ptr<platform::VideoSource> make_source(const RunConfig& config);
/// Every source of source_list(), opened in order (a source that cannot be opened throws its
/// InputError, naming its URI, before anything else is opened), each with its tracker
/// configuration completed from that source and its stream id.
std::vector<pipeline::PipelineInput> make_inputs(const RunConfig& config);
std::unique_ptr<detector::Detector> make_detector(const RunConfig& config);
/// UDP, binary file and JSON lines, in that order, as configured.
std::vector<std::unique_ptr<messages::TrackSink>> make_sinks(const RunConfig& config);
/// The configured tracker with what the file left unset (0) taken from the source.
tracker::TrackerConfig complete_tracker_config(const RunConfig& config,
                                               const platform::SourceInfo& source);
pipeline::PipelineOptions make_options(const RunConfig& config);

}  // namespace rtmot::runner
