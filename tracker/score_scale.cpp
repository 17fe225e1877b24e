#include "tracker/score_scale.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace rtmot::tracker {
namespace {

constexpr float kNoCut = std::numeric_limits<float>::lowest();

std::string describe(const ScoreRange& scores) {
  std::ostringstream text;
  text << "scores range over [" << scores.low << ", " << scores.high << "]";
  return text.str();
}

}  // namespace

std::optional<std::string> score_scale_warning(const TrackerConfig& config,
                                               const ScoreRange& scores) {
  if (scores.count == 0) return std::nullopt;
  std::ostringstream cuts;
  float highest_cut = kNoCut;
  if (config.detection_threshold > kNoCut) {
    cuts << "detection_threshold " << config.detection_threshold;
    highest_cut = config.detection_threshold;
  }
  if (config.second_round && config.low_score > kNoCut) {
    cuts << (highest_cut > kNoCut ? " and " : "") << "low_score " << config.low_score;
    if (highest_cut == kNoCut) highest_cut = config.low_score;
  }
  if (config.birth_threshold > kNoCut) {
    cuts << (highest_cut > kNoCut ? " and " : "") << "birth_threshold " << config.birth_threshold;
    highest_cut = std::max(highest_cut, config.birth_threshold);
  }
  if (cuts.str().empty()) return std::nullopt;  // relative cuts only: any scale fits
  if (scores.low < 0.F || scores.high > 1.F) {
    return describe(scores) + ", not [0, 1]: the absolute cut (" + cuts.str() +
           ") assumes another detector's scale; use score_range_cut instead";
  }
  if (highest_cut > scores.high) {
    return describe(scores) + ": no detection reaches the absolute cut (" + cuts.str() + ")";
  }
  return std::nullopt;
}

}  // namespace rtmot::tracker
