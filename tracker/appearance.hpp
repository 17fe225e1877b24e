#pragma once
// What a detection looks like, as the image layer measured it (vision/): a normalised histogram
// that the tracker compares and averages but never computes. Invalid without images (detection
// files), and then nothing in the tracker changes.
#include <array>

namespace rtmot::tracker {

struct Appearance {
  static constexpr int kBins = 48;
  std::array<float, kBins> bins{};  // non-negative, summing to 1 when valid
  bool valid{false};
};

/// The Hellinger distance, in [0, 1]: 0 for equal histograms, 1 for disjoint ones. Bounded and
/// robust to a few pixels moving between bins, unlike chi-square or L2 on sparse histograms.
float appearance_distance(const Appearance& a, const Appearance& b);

/// `model` after one more sighting: `momentum` of itself and the rest of `seen` (both sum to 1, so
/// the result does); an invalid model becomes `seen`.
void blend_appearance(Appearance& model, const Appearance& seen, float momentum);

}  // namespace rtmot::tracker
