#pragma once
// Opens the source a run configuration names: mot-seq:// (image-less MOTChallenge sequences) here,
// everything else through platform::open_video_source.
#include <memory>
#include <string>

#include "platform/video_source.hpp"

namespace rtmot::runner {

std::unique_ptr<platform::VideoSource> open_source(const std::string& uri,
                                                   const platform::SourceOptions& options);

/// The capture size and rate (source.width/height/fps, --input-width/-height/-rate) are a camera's
/// capture mode: v4l2:// and csi:// take them (and a live stream's cold start uses them until it
/// appears). A recording (file, images://, a test:// that is not live, mot-seq://) plays at its
/// own size and rate: this says so in one line for the log ("" when nothing was asked or the
/// source takes it), so that a jetson-inference user's --input-width on a file is not silently
/// without effect.
std::string ignored_capture_request(const std::string& uri, const platform::SourceOptions& options);

}  // namespace rtmot::runner
