#include "tracker/appearance.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::tracker {

float appearance_distance(const Appearance& a, const Appearance& b) {
  float overlap = 0.F;  // the Bhattacharyya coefficient
  for (int i = 0; i < Appearance::kBins; ++i) overlap += std::sqrt(a.bins[i] * b.bins[i]);
  return std::sqrt(std::max(0.F, 1.F - overlap));
}

void blend_appearance(Appearance& model, const Appearance& seen, float momentum) {
  if (!model.valid) {
    model = seen;
    return;
  }
  for (int i = 0; i < Appearance::kBins; ++i)
    model.bins[i] = momentum * model.bins[i] + (1.F - momentum) * seen.bins[i];
}

}  // namespace rtmot::tracker
