#include "pipeline/annotated_video_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "common/input_error.hpp"

namespace rtmot::pipeline {
namespace {

// A stable, distinct colour per id (golden-ratio hue steps).
cv::Scalar colour_of(std::int32_t id) {
  const double hue = std::fmod(static_cast<double>(id) * 0.618033988749895, 1.0);
  cv::Mat3b hsv(1, 1, cv::Vec3b(static_cast<unsigned char>(hue * 179.0), 220, 255));
  cv::Mat3b bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b pixel = bgr(0, 0);
  return {static_cast<double>(pixel[0]), static_cast<double>(pixel[1]),
          static_cast<double>(pixel[2])};
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

AnnotatedVideoWriter::AnnotatedVideoWriter(std::string path, double fps)
    : path_(std::move(path)), fps_(fps > 0.0 ? fps : 30.0) {}

void AnnotatedVideoWriter::write(cv::Mat& image, const messages::FrameResult& result, double pipeline_fps) {
  if (image.empty()) return;  // an image-less source: nothing to draw on
  if (!writer_.isOpened()) {
    const int codec = ends_with(path_, ".avi") ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                                               : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
    if (!writer_.open(path_, codec, fps_, image.size())) {
      throw InputError(path_, 0, "output.video_file", "cannot open the video file for writing");
    }
  }
  for (const auto& track : result.tracks) {
    const cv::Scalar colour = colour_of(track.id);
    const cv::Rect box(cv::Point(static_cast<int>(track.box.x), static_cast<int>(track.box.y)),
                       cv::Size(static_cast<int>(track.box.w), static_cast<int>(track.box.h)));
    cv::rectangle(image, box, colour, 2);
    cv::putText(image, std::to_string(track.id), box.tl() + cv::Point(2, 16),
                cv::FONT_HERSHEY_SIMPLEX, 0.6, colour, 2);
  }
  cv::putText(image,
              fmt::format("frame {}  {:.1f} fps  {} tracks", result.frame_number, pipeline_fps,
                          result.tracks.size()),
              cv::Point(8, 24), cv::FONT_HERSHEY_SIMPLEX, 0.7, cv::Scalar(0, 255, 255), 2);
  writer_.write(image);
}

}  // namespace rtmot::pipeline
