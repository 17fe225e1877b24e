#pragma once
// The figures the MOTChallenge devkit prints (plus HOTA), all percentages in [0, 100] except FAR
// (false positives per frame) and the counts.
#include <cstdint>

#include "mot/sequence_counts.hpp"

namespace rtmot::mot {

struct Metrics {
  double idf1{0}, idp{0}, idr{0};
  double recall{0}, precision{0}, false_alarms_per_frame{0};
  std::int64_t gt_tracks{0}, mostly_tracked{0}, partly_tracked{0}, mostly_lost{0};
  std::int64_t false_positives{0}, false_negatives{0}, id_switches{0}, fragmentations{0};
  double mota{0}, motp{0}, motal{0};
  double hota{0}, deta{0}, assa{0}, loca{0};
};

Metrics summarize(const SequenceCounts& counts);

}  // namespace rtmot::mot
