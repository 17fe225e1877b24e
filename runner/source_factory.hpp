#pragma once
// Opens the source a run configuration names: mot-seq:// (image-less MOTChallenge sequences) here,
// everything else through platform::open_video_source.
#include <memory>
#include <string>

#include "platform/video_source.hpp"

namespace rtmot::runner {

std::unique_ptr<platform::VideoSource> open_source(const std::string& uri,
                                                   const platform::SourceOptions& options);

}  // namespace rtmot::runner
