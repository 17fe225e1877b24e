#pragma once
// A source turned or mirrored (source.flip, --input-flip: docs/config.md), jetson-inference's
// `--input-flip` with its names: a camera mounted upside down or sideways gives upright frames to
// the detector, the tracker, the messages' boxes and the annotated video alike. Done on every
// source kind in one place (OpenCV on the decoded frame) rather than a videoflip per GStreamer
// pipeline: images:// and mot-seq:// have no pipeline, and a reconnecting camera keeps it.
#include <memory>

#include "platform/video_source.hpp"
#include "tracker/enum_names.hpp"

namespace rtmot::platform {

enum class Orientation {
  none,
  clockwise,             // a quarter turn to the right
  rotate_180,            // upside down
  counterclockwise,      // a quarter turn to the left
  horizontal,            // mirrored left to right
  vertical,              // mirrored top to bottom
  upper_left_diagonal,   // across the upper-left to lower-right diagonal (transposed)
  upper_right_diagonal,  // across the upper-right to lower-left diagonal
};
inline constexpr auto kOrientationNames = tracker::make_enum_names<Orientation>(
    std::pair{Orientation::none, std::string_view("none")},
    std::pair{Orientation::clockwise, std::string_view("clockwise")},
    std::pair{Orientation::rotate_180, std::string_view("rotate-180")},
    std::pair{Orientation::counterclockwise, std::string_view("counterclockwise")},
    std::pair{Orientation::horizontal, std::string_view("horizontal")},
    std::pair{Orientation::vertical, std::string_view("vertical")},
    std::pair{Orientation::upper_left_diagonal, std::string_view("upper-left-diagonal")},
    std::pair{Orientation::upper_right_diagonal, std::string_view("upper-right-diagonal")});

/// Whether the orientation swaps width and height.
bool swaps_sides(Orientation orientation);

/// Writes `in` turned or mirrored into `out` (reusing its buffer when the size is unchanged;
/// `scratch` holds the intermediate of the one orientation that needs two steps). `in` and `out`
/// must differ.
void orient(const cv::Mat& in, cv::Mat& out, Orientation orientation, cv::Mat& scratch);

class OrientedSource final : public VideoSource {
 public:
  OrientedSource(std::unique_ptr<VideoSource> inner, Orientation orientation);

  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override;
  /// The inner source's, with width and height swapped by a quarter turn.
  const SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return inner_->last_error(); }
  bool reconnecting() const override { return inner_->reconnecting(); }

 private:
  std::unique_ptr<VideoSource> inner_;
  Orientation orientation_;
  SourceInfo info_;
  cv::Mat decoded_;
  cv::Mat scratch_;
};

}  // namespace rtmot::platform
