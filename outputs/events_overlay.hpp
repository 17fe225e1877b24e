#pragma once
// The counting lines and zones on the annotated video, with their live counts: each line with its
// name and "in N / out M", each zone outlined with its name and how many are inside now. The
// counts are summed from the events each processed frame carries (the same the messages and the
// metrics get), so the picture shows what a ground station counts.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "events/events_config.hpp"
#include "messages/frame_result.hpp"

namespace rtmot::outputs {

class EventsOverlay {
 public:
  explicit EventsOverlay(events::EventsConfig config);

  /// Adds a processed frame's events to the counts.
  void count(const messages::FrameResult& result);
  /// Draws every line and zone with its counts onto `image` (BGR).
  void draw(cv::Mat& image);

  std::int64_t line_in(std::size_t line) const { return lines_[line].in; }
  std::int64_t line_out(std::size_t line) const { return lines_[line].out; }
  std::int64_t occupancy(std::size_t zone) const { return occupancy_[zone]; }

 private:
  events::EventsConfig config_;
  std::vector<events::LineCounts> lines_;
  std::vector<std::int64_t> occupancy_;
  std::vector<std::vector<cv::Point>> polygons_;  // the zones in integer pixels, made once
  std::string text_;                              // reused for each label
};

}  // namespace rtmot::outputs
