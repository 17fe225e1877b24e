#pragma once
// Which GStreamer pipeline captures which kind of URI. Descriptions hold no user text: the file
// path, device, URL and numbers are set as element properties afterwards, so no quoting can go
// wrong.
#include <gst/gst.h>

#include <string>

#include "platform/video_source.hpp"
#include "platform/video_uri.hpp"

namespace rtmot::platform::gst {

/// A gst_parse_launch description whose source is named "src" and whose appsink is named "sink".
std::string pipeline_description(SourceKind kind);

/// Sets the URI's location/device/sensor, the requested size and rate, the test pattern and faults
/// (except stalls), and the appsink's policy: every frame for files, only the newest when live.
/// Throws rtmot::InputError (source_failed) for values the elements reject.
void configure_pipeline(GstBin& pipeline, const VideoUri& uri, const SourceOptions& options);

}  // namespace rtmot::platform::gst
