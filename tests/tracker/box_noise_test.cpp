// The stream's box noise: the median offset of matched detections from their predictions, as a
// share of the box size; and the gate it widens keeping one identity through a jittery detector.
#include "tracker/box_noise.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {

// Offsets 0, 0.05, ..., 0.45 (dx of 0..9 tenths of a fifth of the width, dy 0), `rounds` times.
BoxNoise fed(float scale, int rounds, int window = 512) {
  BoxNoise noise(window);
  const Box predicted{100.F * scale, 200.F * scale, 40.F * scale, 80.F * scale};
  for (int r = 0; r < rounds; ++r) {
    for (int k = 0; k < 10; ++k) {
      Box detection = predicted;
      detection.x += 4.F * scale * static_cast<float>(k);
      noise.observe(predicted, detection);
    }
  }
  return noise;
}

TEST(BoxNoise, TheMedianOffsetIsAShareOfTheBoxSize) {
  EXPECT_DOUBLE_EQ(BoxNoise(512).median_offset(), 0.0);  // nothing seen
  const BoxNoise noise = fed(1.F, 30);
  EXPECT_NEAR(noise.median_offset(), 0.225, 0.03);
  // The same offsets relative to boxes ten times larger: the same noise.
  EXPECT_NEAR(fed(10.F, 30).median_offset(), noise.median_offset(), 1e-6);
}

TEST(BoxNoise, AWindowOfNothingMeasuresNothingAndResetForgets) {
  EXPECT_DOUBLE_EQ(fed(1.F, 30, 0).median_offset(), 0.0);
  BoxNoise noise = fed(1.F, 30);
  noise.reset();
  EXPECT_DOUBLE_EQ(noise.median_offset(), 0.0);
}

// One walker seen every frame through a detector whose box centres jitter by `jitter` x the size:
// how many identities it is reported under.
int identities(double noise_gate_factor, float jitter) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 5;
  config.noise_gate_factor = noise_gate_factor;
  Tracker tracker(config);
  std::mt19937 engine(11);
  std::normal_distribution<float> normal(0.F, 1.F);
  std::vector<int> ids;
  for (int frame = 1; frame <= 300; ++frame) {
    const float x = 100.F + 2.F * static_cast<float>(frame) + jitter * 40.F * normal(engine);
    const float y = 200.F + jitter * 80.F * normal(engine);
    for (const TrackReport& report :
         tracker.update({Detection{Box{x, y, 40.F, 80.F}, 0.9F, 1}}, frame / 30.0)) {
      if (std::find(ids.begin(), ids.end(), report.id) == ids.end()) ids.push_back(report.id);
    }
  }
  return static_cast<int>(ids.size());
}

TEST(NoiseGate, KeepsOneIdentityThroughAJitteryDetector) {
  const int plain = identities(0.0, 0.2F);
  const int widened = identities(3.0, 0.2F);
  RecordProperty("identities_plain", plain);
  RecordProperty("identities_widened", widened);
  EXPECT_GT(plain, 5) << "the scene must be jittery enough to break IoU 0.3";
  EXPECT_EQ(widened, 1);
  // A steady detector: nothing to widen, the same result either way.
  EXPECT_EQ(identities(3.0, 0.01F), identities(0.0, 0.01F));
}

}  // namespace
}  // namespace rtmot::tracker
