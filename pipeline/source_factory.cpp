#include "pipeline/source_factory.hpp"

#include "pipeline/sequence_clock_source.hpp"

namespace rtmot::pipeline {

std::unique_ptr<platform::VideoSource> open_source(const std::string& uri,
                                                   const platform::SourceOptions& options) {
  if (is_sequence_uri(uri)) return std::make_unique<SequenceClockSource>(uri);
  return platform::open_video_source(uri, options);
}

}  // namespace rtmot::pipeline
