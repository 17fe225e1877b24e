#pragma once
// How long the detector was busy: the union of the intervals during which some lane was inside
// its detector, given in the order the batches were handed on (sorted by start, but for the few
// microseconds between two lanes waking up). The detect stage counts it for the run's report
// (detector_fps, "capacity") and the metrics count it from the messages' detect stamps for the
// web page's live figure: one definition of "capacity".
#include <algorithm>
#include <cstdint>

namespace rtmot::pipeline {

class BusyTime {
 public:
  /// One interval [start_ns, end_ns]; a part already covered is not counted again.
  void add(std::int64_t start_ns, std::int64_t end_ns) {
    const std::int64_t from = std::max(start_ns, busy_until_ns_);
    if (end_ns > from) busy_ns_ += end_ns - from;
    busy_until_ns_ = std::max(busy_until_ns_, end_ns);
  }
  std::int64_t busy_ns() const { return busy_ns_; }

 private:
  std::int64_t busy_ns_{0};
  std::int64_t busy_until_ns_{0};  // end of the union so far
};

}  // namespace rtmot::pipeline
