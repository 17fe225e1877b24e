#include "tracker/particle_predictor.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tracker/box_geometry.hpp"

namespace rtmot::tracker {
namespace {
// Noise per sqrt(nominal frame), relative to the box size: a pedestrian at 30 fps moves a few
// percent of its width per frame and changes size more slowly.
constexpr float kPositionNoise = 0.05F;
constexpr float kSizeNoise = 0.02F;
constexpr float kInitialSpread = 0.05F;
// How much a new velocity measurement counts against the running estimate.
constexpr float kVelocityGain = 0.5F;
// Likelihood of a particle: exp(-(1 - IoU) / width). IoU itself as the weight is too flat (a
// cloud a few percent wide scores 0.8..0.9 everywhere) to pull the estimate onto the detection.
// 0.01 was the best of 0.005..0.3 on MOT15-train (MOTA 37.5 with IoU association; 21.6 with raw
// IoU weights).
constexpr float kLikelihoodWidth = 0.01F;
// Below this total the cloud has lost the object.
constexpr float kWeightFloor = 1e-12F;

// SplitMix64 finaliser: decorrelates the streams of tracks whose ids differ by one.
std::uint64_t mix(std::uint64_t seed, std::uint64_t id) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (id + 1);
  z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31U);
}

// Spread of one 16-bit uniform on 0..65535, and of the sum of four.
constexpr float kUniform16Mean = 32767.5F;
constexpr float kSumOfFourSd = 2.F * 18918.6F;  // 2 * sqrt((65536^2 - 1) / 12)

Box to_box(const Particle& p) {
  return Box{p.cx - p.w / 2.F, p.cy - p.h / 2.F, p.w, p.h};
}
}  // namespace

ParticlePredictor::ParticlePredictor(const Box& box, ParticleStorage storage, std::uint64_t seed,
                                     std::int32_t track_id)
    : storage_(storage),
      rng_(mix(seed, static_cast<std::uint64_t>(track_id))),
      estimate_(box),
      last_observation_(box) {
  scatter_around(box);
}

void ParticlePredictor::scatter_around(const Box& box) {
  const float weight = 1.F / static_cast<float>(storage_.count);
  for (int i = 0; i < storage_.count; ++i) {
    Particle& p = storage_.front[i];
    p.cx = box.center_x() + kInitialSpread * box.w * normal();
    p.cy = box.center_y() + kInitialSpread * box.h * normal();
    p.w = box.w * (1.F + kInitialSpread * normal());
    p.h = box.h * (1.F + kInitialSpread * normal());
    p.weight = weight;
  }
}

// Standard normal approximated by the sum of the four 16-bit uniforms of one 64-bit draw
// (Irwin-Hall, scaled to unit variance; tails end at 3.5 sigma, which propagation noise does not
// miss). Hand-written because std::normal_distribution (log plus rejection) took two thirds of the
// particle filter's time in tracker_bench; this is one engine call and no transcendental.
float ParticlePredictor::normal() {
  const std::uint64_t bits = rng_();
  float sum = 0.F;
  for (unsigned k = 0; k < 4; ++k) sum += static_cast<float>((bits >> (16U * k)) & 0xFFFFU);
  return (sum - 4.F * kUniform16Mean) / kSumOfFourSd;
}

Box ParticlePredictor::mean() const {
  double cx = 0.0;
  double cy = 0.0;
  double w = 0.0;
  double h = 0.0;
  double total = 0.0;
  for (int i = 0; i < storage_.count; ++i) {
    const Particle& p = storage_.front[i];
    cx += double{p.weight} * p.cx;
    cy += double{p.weight} * p.cy;
    w += double{p.weight} * p.w;
    h += double{p.weight} * p.h;
    total += p.weight;
  }
  if (!(total > 0.0)) return estimate_;
  const auto width = static_cast<float>(w / total);
  const auto height = static_cast<float>(h / total);
  return Box{static_cast<float>(cx / total) - width / 2.F,
             static_cast<float>(cy / total) - height / 2.F, width, height};
}

Box ParticlePredictor::predict(double dt) {
  const auto step = static_cast<float>(dt);
  const float spread = std::sqrt(std::max(step, 0.F));
  const float dx = has_velocity_ ? velocity_x_ * step : 0.F;
  const float dy = has_velocity_ ? velocity_y_ * step : 0.F;
  for (int i = 0; i < storage_.count; ++i) {
    Particle& p = storage_.front[i];
    p.cx += dx + kPositionNoise * spread * p.w * normal();
    p.cy += dy + kPositionNoise * spread * p.h * normal();
    // Sizes change multiplicatively and stay positive.
    p.w *= std::exp(kSizeNoise * spread * normal());
    p.h *= std::exp(kSizeNoise * spread * normal());
  }
  frames_since_observation_ += dt;
  estimate_ = mean();
  return estimate_;
}

Box ParticlePredictor::peek(double dt) const {
  if (!has_velocity_) return estimate_;
  const auto step = static_cast<float>(dt);
  Box ahead = estimate_;
  ahead.x += velocity_x_ * step;
  ahead.y += velocity_y_ * step;
  return ahead;
}

void ParticlePredictor::update(const Box& box) {
  double total = 0.0;
  for (int i = 0; i < storage_.count; ++i) {
    Particle& p = storage_.front[i];
    const float overlap = iou(to_box(p), box);
    p.weight = overlap > 0.F ? std::exp(-(1.F - overlap) / kLikelihoodWidth) : 0.F;
    total += p.weight;
  }
  if (total <= kWeightFloor) {
    // No particle overlaps the observation the tracker accepted: the cloud has lost the object.
    scatter_around(box);
  }
  estimate_ = mean();

  if (frames_since_observation_ > 0.0) {
    const auto frames = static_cast<float>(frames_since_observation_);
    const float vx = (box.center_x() - last_observation_.center_x()) / frames;
    const float vy = (box.center_y() - last_observation_.center_y()) / frames;
    velocity_x_ = has_velocity_ ? velocity_x_ + kVelocityGain * (vx - velocity_x_) : vx;
    velocity_y_ = has_velocity_ ? velocity_y_ + kVelocityGain * (vy - velocity_y_) : vy;
    has_velocity_ = true;
  }
  last_observation_ = box;
  frames_since_observation_ = 0.0;
  resample();
}

// Systematic resampling: one uniform draw, then evenly spaced pointers through the cumulative
// weights; low variance and O(n).
void ParticlePredictor::resample() {
  const int n = storage_.count;
  double total = 0.0;
  for (int i = 0; i < n; ++i) total += storage_.front[i].weight;
  const double step = total / n;
  double position = std::uniform_real_distribution<double>(0.0, step)(rng_);
  double cumulative = storage_.front[0].weight;
  int source = 0;
  const float weight = 1.F / static_cast<float>(n);
  for (int i = 0; i < n; ++i) {
    while (position > cumulative && source < n - 1) {
      ++source;
      cumulative += storage_.front[source].weight;
    }
    storage_.back[i] = storage_.front[source];
    storage_.back[i].weight = weight;
    position += step;
  }
  std::swap(storage_.front, storage_.back);
}

}  // namespace rtmot::tracker
