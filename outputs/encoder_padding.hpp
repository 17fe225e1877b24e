#pragma once
// The one place that fits a frame to what the video encoder takes, for every encoder output and
// codec: the file, RTP and display pipelines (outputs/gst_video_output.cpp), built when the size is
// known, and the RTSP server (outputs/rtsp_video_server.cpp), whose pipeline exists before it is.
#include <gst/gst.h>

#include <string>

#include "outputs/video_encoding.hpp"

namespace rtmot::outputs {

/// Black added on the right and bottom.
struct EncoderPadding {
  int right{0};
  int bottom{0};
  bool none() const { return right == 0 && bottom == 0; }
};

/// The smallest side the encoders of `codec` take (4:2:0 frames: sides are also even).
/// H.264: 16, x264's smallest (33x17 and 1x1 were refused at the first frame, 16x14 hung it).
/// H.265: 64, x265's largest coding tree unit. x265 wants a picture of at least one CTU; given
/// less it shrinks the CTU, and on that path x265 3.5 writes past its buffers (34x18, 40x18:
/// "free(): invalid next size", SIGABRT). At 64 no preset's CTU is shrunk.
int min_encoder_side(VideoCodec codec);

/// The padding up to the nearest size the encoders of `codec` take.
EncoderPadding encoder_padding_of(VideoCodec codec, int width, int height);

/// The padding as a pipeline fragment: "videobox right=-1 bottom=-1 ! ", or "" when none.
std::string encoder_padding(VideoCodec codec, int width, int height);

/// For a pipeline built before the frame size is known: a videobox named "pad" (passing frames
/// through until sized) that set_encoder_padding() sizes at the first frame.
constexpr const char* kSizedLaterPadding = "videobox name=pad ! ";
void set_encoder_padding(GstElement* videobox, VideoCodec codec, int width, int height);

/// The warning an output logs once when its frames are padded (`output`: its URI as given),
/// naming the codec and the encoder element that needs it.
void warn_if_padded(const std::string& output, const VideoEncoder& encoder, int width, int height);

}  // namespace rtmot::outputs
