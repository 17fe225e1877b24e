#pragma once
// A GStreamer buffer holding a copy of an 8-bit BGR image, rows padded to 4 bytes (what
// `video/x-raw,format=BGR` caps describe when no GstVideoMeta says otherwise). One copy is
// unavoidable: the pipeline reuses its images as soon as a consumer returns, while GStreamer keeps
// buffers until its encoder or server is done with them.
#include <gst/gst.h>

#include <opencv2/core/mat.hpp>

namespace rtmot::outputs {

/// A new buffer (owned by the caller; push_buffer takes it over) with `bgr`'s pixels.
GstBuffer* copy_to_gst_buffer(const cv::Mat& bgr);

}  // namespace rtmot::outputs
