// run_setup.hpp's sources: each configured source opened (looped, turned) as a pipeline input.
#include <spdlog/spdlog.h>

#include "platform/looping_source.hpp"
#include "platform/oriented_source.hpp"
#include "runner/run_setup.hpp"
#include "runner/source_factory.hpp"

namespace rtmot::runner {
namespace {

std::unique_ptr<platform::VideoSource> open_configured(const SourceConfig& source) {
  platform::SourceOptions options;
  options.width = source.width;
  options.height = source.height;
  options.fps = source.fps;
  const std::string ignored = ignored_capture_request(source.uri, options);
  if (!ignored.empty()) spdlog::warn("{}", ignored);
  std::unique_ptr<platform::VideoSource> opened;
  if (source.loop != 0) {  // a file (validate() refused a live source)
    opened = std::make_unique<platform::LoopingSource>(
        [uri = source.uri, options] { return open_source(uri, options); }, source.loop);
  } else {
    opened = open_source(source.uri, options);
  }
  if (source.flip != platform::Orientation::none) {
    spdlog::info("{}: every frame turned {}", source.uri,
                 platform::kOrientationNames.name(source.flip));
    opened = std::make_unique<platform::OrientedSource>(std::move(opened), source.flip);
  }
  return opened;
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
    inputs[i].events =
        events::resolve_events(sources[i].events, static_cast<int>(inputs[i].tracker.image_width),
                               static_cast<int>(inputs[i].tracker.image_height));
    inputs[i].events.frame_period_seconds = 1.0 / inputs[i].tracker.frame_rate;
  }
  return inputs;
}

}  // namespace rtmot::runner
