#pragma once
// Whether a detector's scores fit the absolute score cuts of a configuration. The relative cuts
// (score_range_cut) fit any scale; an absolute one (detection_threshold, the
// second round's low_score, a replay detector's score_threshold) is a number on one detector's
// scale, and on another it silently drops everything or nothing.
#include <optional>
#include <string>

#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

/// The lowest and highest finite score seen.
struct ScoreRange {
  float low{0.F};
  float high{0.F};
  long long count{0};

  void include(float score) {
    if (!(score == score) || score - score != 0.F) return;  // NaN or infinite
    low = count == 0 ? score : (score < low ? score : low);
    high = count == 0 ? score : (score > high ? score : high);
    ++count;
  }
};

/// A warning (without the file's name) when `config` has an absolute score cut and `scores` look
/// like another scale: outside [0, 1] (the scale the presets' and options' absolute numbers are
/// on), or wholly on one side of the cut. nullopt when nothing is amiss or nothing was seen.
std::optional<std::string> score_scale_warning(const TrackerConfig& config,
                                               const ScoreRange& scores);

}  // namespace rtmot::tracker
