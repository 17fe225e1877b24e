#include "events/offline_count.hpp"

#include <algorithm>

#include "events/event_counter.hpp"

namespace rtmot::events {

SequenceCounts count_sequence(const std::vector<FrameTrack>& tracks, int length, double frame_rate,
                              int interval, const EventsConfig& config) {
  std::vector<FrameTrack> sorted = tracks;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const FrameTrack& a, const FrameTrack& b) { return a.frame < b.frame; });
  EventsConfig timed = config;
  timed.frame_period_seconds = frame_rate > 0.0 ? 1.0 / frame_rate : 0.0;
  EventCounter counter(timed);
  std::vector<tracker::TrackReport> reports;
  auto next = sorted.begin();
  double time = 0.0;
  for (long frame = 1; frame <= length; frame += std::max(interval, 1)) {
    while (next != sorted.end() && next->frame < frame) ++next;
    reports.clear();
    for (; next != sorted.end() && next->frame == frame; ++next) reports.push_back(next->report);
    time = static_cast<double>(frame - 1) / frame_rate;
    counter.update(reports, time);
  }
  counter.finish(time);
  return {counter.line_counts(), counter.zone_counts(), counter.box_noise()};
}

}  // namespace rtmot::events
