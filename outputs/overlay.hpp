#pragma once
// What the annotated video shows, as jetson-inference's --overlay flags: box, labels (id and class
// name on a filled background), conf (score), track (the id), trail (the last positions), stats
// (an FPS/latency line). Frames the detector did not process carry the tracks' predicted boxes,
// drawn dashed and thin so that they read as predictions.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "messages/frame_result.hpp"
#include "messages/jsonl_sink.hpp"

namespace rtmot::outputs {

enum class OverlayFlag : unsigned {
  box = 1U << 0,
  labels = 1U << 1,
  conf = 1U << 2,
  track = 1U << 3,
  trail = 1U << 4,
  stats = 1U << 5,
};

struct OverlayFlags {
  unsigned bits{0};
  bool has(OverlayFlag flag) const { return (bits & static_cast<unsigned>(flag)) != 0; }
};

/// "box,labels,conf,track,trail,stats" (any subset, any order) or "none". nullopt with `problem`.
std::optional<OverlayFlags> parse_overlay_flags(const std::string& text, std::string& problem);
/// Every flag's name, "box, labels, ... or stats" (for help texts).
std::string overlay_flag_names();

/// The numbers the stats line shows.
struct OverlayStats {
  double fps{0.0};         // the pipeline's recent rate (pipeline::SinkFrame::recent_fps)
  double latency_ms{0.0};  // capture -> sent of the latest processed frame
};

/// Sizes of the drawing for a frame height: text, lines and padding scale with the frame.
struct OverlayStyle {
  double font_scale{0.5};
  int font_thickness{1};
  int line_thickness{2};
  int pad{2};
  int baseline{0};
  int text_height{0};
  static OverlayStyle for_height(int rows);
};

class Overlay {
 public:
  /// `max_tracks` trails are kept (more tracks draw no trail), `trail_length` points each; both
  /// preallocated here, so drawing allocates nothing per frame.
  Overlay(OverlayFlags flags, messages::ClassLabelFn labels, std::size_t max_tracks = 256,
          std::size_t trail_length = 24);

  /// Draws `result`'s tracks onto `image`. `predicted`: the boxes are the tracker's predictions
  /// for a frame the detector skipped (dashed, no score, trails not extended).
  void draw(cv::Mat& image, const messages::FrameResult& result, bool predicted,
            const OverlayStats& stats);

 private:
  struct Trail {
    std::int32_t id{-1};
    std::int64_t last_frame{0};
    std::size_t next{0};
    std::size_t size{0};
    std::vector<cv::Point> points;
  };
  Trail* trail_of(std::int32_t id, std::int64_t frame);
  cv::Size label_size(const std::string& text) const;
  static cv::Rect box_of(const tracker::TrackReport& track);

  OverlayFlags flags_;
  messages::ClassLabelFn labels_;
  std::vector<Trail> trails_;
  std::string text_;              // reused for each label
  std::vector<cv::Rect> placed_;  // this frame's labels so far (reserved: no allocation per frame)
  OverlayStyle style_;
  int style_rows_{-1};  // the frame height style_ was made for
};

/// A stable, distinct colour per track id (golden-ratio hue steps), BGR: the trails.
cv::Scalar colour_of(std::int32_t id);
/// Where a label of `size` for `box` goes in an image of `image` size so that it overlaps none of
/// `placed`: above the box, inside its top, below it, else the nearest free place above or below.
cv::Rect place_label(const cv::Size& size, const cv::Rect& box, const cv::Size& image,
                     const std::vector<cv::Rect>& placed);

/// The colour of a class (COCO id), BGR: boxes and labels (DeepStream's convention).
cv::Scalar class_colour(std::int32_t class_id);

}  // namespace rtmot::outputs
