#pragma once
// A bootstrap particle filter over boxes (centre, size) with a constant-velocity drift.
// Particles live in storage the Tracker preallocates per track slot; the filter only points at it.
#include <cstdint>
#include <random>

#include "tracker/box.hpp"

namespace rtmot::tracker {

struct Particle {
  float cx{0.F};
  float cy{0.F};
  float w{0.F};
  float h{0.F};
  float weight{0.F};
};

/// A slot's particle storage: two buffers of `count` particles (resampling swaps them).
struct ParticleStorage {
  Particle* front{nullptr};
  Particle* back{nullptr};
  int count{0};
};

class ParticlePredictor {
 public:
  /// Spreads the particles around `box`. The random stream depends on `seed` and `track_id` only,
  /// so a run is reproducible.
  ParticlePredictor(const Box& box, ParticleStorage storage, std::uint64_t seed,
                    std::int32_t track_id);

  /// Drifts every particle by the velocity estimate plus noise that grows with `dt`.
  Box predict(double dt);
  /// Weighs particles by their IoU with the observed box, estimates, then resamples
  /// systematically.
  void update(const Box& box);
  Box box() const { return estimate_; }
  /// The estimate drifted by the velocity estimate over `dt` nominal frames, without noise and
  /// without touching the particles (their storage is shared with the live filter, and drawing
  /// noise would advance the random stream): what predict(dt) moves the cloud's mean by.
  Box peek(double dt) const;

 private:
  void scatter_around(const Box& box);
  Box mean() const;
  void resample();
  float normal();

  ParticleStorage storage_;
  std::mt19937_64 rng_;
  Box estimate_;
  Box last_observation_;
  float velocity_x_{0.F};  // centre motion per nominal frame
  float velocity_y_{0.F};
  double frames_since_observation_{0.0};
  bool has_velocity_{false};
};

}  // namespace rtmot::tracker
