#pragma once
// Helpers for small synthetic scenes.
#include <algorithm>
#include <vector>

#include "tracker/box.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::test {

inline tracker::Detection detection(float x, float y, float w = 40.F, float h = 80.F,
                                    float score = 0.9F) {
  return tracker::Detection{tracker::Box{x, y, w, h}, score, 1};
}

inline bool reports_id(const std::vector<tracker::TrackReport>& reports, int id) {
  return std::any_of(reports.begin(), reports.end(),
                     [id](const tracker::TrackReport& r) { return r.id == id; });
}

}  // namespace rtmot::test
