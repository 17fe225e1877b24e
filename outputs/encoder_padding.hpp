#pragma once
// The one place that fits a frame to what the H.264 encoder takes, for every encoder output: the
// file, RTP and display pipelines (outputs/gst_video_output.cpp), built when the size is known,
// and the RTSP server (outputs/rtsp_video_server.cpp), whose pipeline exists before it is.
#include <gst/gst.h>

#include <string>

namespace rtmot::outputs {

/// Black added on the right and bottom.
struct EncoderPadding {
  int right{0};
  int bottom{0};
  bool none() const { return right == 0 && bottom == 0; }
};

/// x264 takes 4:2:0 frames whose sides are even and at least 16 (33x17 and 1x1 were refused at
/// the first frame, 16x14 hung it): the padding up to the nearest size it takes.
EncoderPadding encoder_padding_of(int width, int height);

/// The padding as a pipeline fragment: "videobox right=-1 bottom=-1 ! ", or "" when none.
std::string encoder_padding(int width, int height);

/// For a pipeline built before the frame size is known: a videobox named "pad" (passing frames
/// through until sized) that set_encoder_padding() sizes at the first frame.
constexpr const char* kSizedLaterPadding = "videobox name=pad ! ";
void set_encoder_padding(GstElement* videobox, int width, int height);

/// The warning an output logs once when its frames are padded (`output`: its URI as given).
void warn_if_padded(const std::string& output, int width, int height);

}  // namespace rtmot::outputs
