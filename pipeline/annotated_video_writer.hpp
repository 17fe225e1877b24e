#pragma once
// The optional annotated video (output.video_file): each processed frame with its track boxes, ids
// and the pipeline's FPS, written by the sink stage. Costs an image hand-over per frame (a cv::Mat
// swap through the queues, no copy) plus the encoding, so it is off unless configured.
#include <opencv2/core/mat.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "messages/frame_result.hpp"

namespace rtmot::pipeline {

class AnnotatedVideoWriter {
 public:
  /// `fps` is the rate written into the file (the source's nominal rate). The file is opened at the
  /// first frame, when its size is known; .avi gets MJPG, anything else mp4v.
  AnnotatedVideoWriter(std::string path, double fps);
  /// Draws onto `image` (it is the pipeline's own buffer) and appends it. Throws InputError
  /// (output.video_file) if the file cannot be opened.
  void write(cv::Mat& image, const messages::FrameResult& result, double pipeline_fps);
  void close() { writer_.release(); }

 private:
  std::string path_;
  double fps_;
  cv::VideoWriter writer_;
};

}  // namespace rtmot::pipeline
