#include "study/study_knobs.hpp"

#include <limits>
#include <memory>

#include "tracker/score_cut.hpp"

namespace rtmot::study {
namespace {

constexpr float kNoCut = std::numeric_limits<float>::lowest();

class StudyExtension final : public tracker::TrackerExtension {
 public:
  StudyExtension(const StudyKnobs& knobs, const tracker::TrackerConfig& config)
      : knobs_(knobs),
        strong_births_(config.strong_birth_range_cut > 0.0),
        // Its own window of the same length as the tracker's: the quantile is taken over the same
        // scores on the same schedule as when it was a tracker setting.
        quantile_(knobs.score_quantile, 0.0, tracker::kScoreWindow) {}

  bool needs_score_range() const override {
    return knobs_.birth_range_cut > 0.0 || knobs_.confirm_score_cut > 0.0;
  }
  bool cascades() const override { return knobs_.recent_tracks_first; }

  float split_cut(const std::vector<tracker::Detection>& detections) override {
    return quantile_.observe(detections);
  }

  float birth_cut(const tracker::ScoreCut& scores) const override {
    return knobs_.birth_range_cut > 0.0 ? scores.range_point(knobs_.birth_range_cut) : kNoCut;
  }

  bool defers(const tracker::TrackFacts& track) const override {
    return knobs_.recent_tracks_first && track.steps_since_update != 1;
  }

  // A false positive that recurs at one place is matched often but scores low on average; a
  // person seen half-occluded scores low only for a while.
  bool may_confirm(const tracker::TrackFacts& track,
                   const tracker::ScoreCut& scores) const override {
    if (knobs_.confirm_score_cut <= 0.0 || track.matches == 0) return true;
    return track.score_sum / track.matches >= scores.range_point(knobs_.confirm_score_cut);
  }

  bool may_confirm_by_duration(const tracker::TrackFacts& track) const override {
    return !(knobs_.weak_births_by_count && strong_births_ && !track.strong_birth);
  }

  void reset() override { quantile_.reset(); }

 private:
  StudyKnobs knobs_;
  bool strong_births_;
  tracker::ScoreCut quantile_;
};

}  // namespace

StudyKnobs merged(StudyKnobs a, const StudyKnobs& b) {
  if (b.score_quantile > 0.0) a.score_quantile = b.score_quantile;
  if (b.birth_range_cut > 0.0) a.birth_range_cut = b.birth_range_cut;
  if (b.confirm_score_cut > 0.0) a.confirm_score_cut = b.confirm_score_cut;
  a.weak_births_by_count = a.weak_births_by_count || b.weak_births_by_count;
  a.recent_tracks_first = a.recent_tracks_first || b.recent_tracks_first;
  return a;
}

tracker::TrackerExtensionFactory study_extension(const StudyKnobs& knobs,
                                                 const tracker::TrackerConfig& config) {
  if (!knobs.any()) return {};
  return [knobs, config]() -> std::unique_ptr<tracker::TrackerExtension> {
    return std::make_unique<StudyExtension>(knobs, config);
  };
}

}  // namespace rtmot::study
