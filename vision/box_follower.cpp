#include "vision/box_follower.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rtmot::vision {
namespace {

// The part of a box whose points are followed: the middle 60 % of its width (a person's box holds
// background at its sides, which stays where it is) and 10..90 % of its height (the head's top and
// the feet, whose ground moves nowhere while the feet swing, are left out).
constexpr float kInnerLeft = 0.2F;
constexpr float kInnerRight = 0.8F;
constexpr float kInnerTop = 0.1F;
constexpr float kInnerBottom = 0.9F;
// Points nearer each other than this (thumbnail px) sample the same pixels: a small box gets fewer.
constexpr float kMinSpacing = 2.F;
// Fewer points than this give no median worth moving a box by.
constexpr int kMinPoints = 4;
// A pair of points nearer than this (thumbnail px) says nothing of scale: sub-pixel noise.
constexpr float kMinPairDistance = 3.F;
// One frame's change of size is bounded: people do not grow by a quarter between camera frames,
// and a few points of the background agreeing with each other must not blow a box up.
constexpr float kMinScaleStep = 0.8F;
constexpr float kMaxScaleStep = 1.25F;
// A trusted point agrees with its box's motion when it went within this (thumbnail px) of where
// the box's motion and scale take it: a walking person's limbs swing more than that, their torso
// and head do not. On S2L1 (tests) 1.5 to 3 gave the same IoU; 1 dropped a tenth of the steps.
constexpr float kMaxDisagreement = 2.F;
// Lucas-Kanade's iterations per pyramid level. Most points converge in a few; those that do not
// (little texture, a moving edge) cost the most and are rarely trusted anyway. On S2L1 (tests)
// 10 instead of OpenCV's 30 or 20 gave the same IoU and sub-pixel shifts at about 2/3 the time.
constexpr int kIterations = 10;

LucasKanadeConfig lucas_kanade_of(const BoxFollowerConfig& config) {
  LucasKanadeConfig lk;
  lk.window = config.window;
  lk.levels = config.pyramid_levels;
  lk.iterations = kIterations;
  return lk;
}

bool usable(const tracker::Box& box) {
  return std::isfinite(box.x) && std::isfinite(box.y) && std::isfinite(box.w) &&
         std::isfinite(box.h) && box.w > 0.F && box.h > 0.F;
}

// The median of values[0..count) (reorders them); count > 0.
float median(std::vector<float>& values, std::size_t count) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(values.begin(), middle, values.begin() + static_cast<std::ptrdiff_t>(count));
  return *middle;
}

}  // namespace

BoxFollower::BoxFollower(const BoxFollowerConfig& config) : config_(config) {
  if (config_.grid < 2 || config_.window < 3 || config_.pyramid_levels < 0 ||
      !(config_.max_round_trip > 0.F) ||
      !(config_.min_trusted >= 0.F && config_.min_trusted <= 1.F))
    throw std::invalid_argument(
        "BoxFollowerConfig: grid >= 2, window >= 3, pyramid_levels >= 0, max_round_trip > 0 and "
        "min_trusted in [0, 1] are required");
  // One box's points at most: the per-box buffers never grow after this.
  const auto per_box =
      static_cast<std::size_t>(config_.grid) * static_cast<std::size_t>(config_.grid);
  trusted_.reserve(per_box);
  scratch_.reserve(per_box);
}

void BoxFollower::push(const cv::Mat& gray_thumbnail, float scale) {
  if (gray_thumbnail.empty() || gray_thumbnail.type() != CV_8UC1 || !(scale > 0.F) ||
      !std::isfinite(scale))
    throw std::invalid_argument(
        "BoxFollower::push: an 8-bit gray thumbnail and a scale > 0 are "
        "required (got type " +
        std::to_string(gray_thumbnail.type()) + ", " + std::to_string(gray_thumbnail.cols) + "x" +
        std::to_string(gray_thumbnail.rows) + ")");
  // Another size or scale than the last frame's is another camera set-up: nothing to follow across.
  if (frames_ > 0 && (latest_.levels() == 0 || latest_.image(0).size() != gray_thumbnail.size() ||
                      scale != scale_))
    frames_ = 0;
  // The previous frame's pyramid becomes the one to follow from; its buffers are rebuilt in place
  // for the new frame (same size: no allocation). Derivatives are kept with each level because
  // every frame is the start of a flow twice: forwards from it once it is the previous frame, and
  // backwards from it (the round-trip check) while it is the latest. The input is converted into
  // the pyramid, never referenced: the caller reuses its thumbnail buffer. OpenCV's pyrDown and
  // Scharr allocate small row scratch inside (OpenCV 4.6, counted with malloc interposed for its
  // own pyramid builder, which runs the same filters: a few blocks, about 9 KB a push of 384x288).
  std::swap(previous_, latest_);
  latest_.build(gray_thumbnail, lucas_kanade_of(config_));
  scale_ = scale;
  frames_ = std::min(frames_ + 1, 2);
}

bool BoxFollower::ready() const {
  return frames_ >= 2;
}

void BoxFollower::reset() {
  frames_ = 0;
}

void BoxFollower::follow(const std::vector<tracker::Box>& boxes, std::vector<FollowedBox>& out) {
  out.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) out[i] = FollowedBox{boxes[i], 0.F, false};
  if (!ready() || boxes.empty()) return;

  // Every box's grid of points, in one list (one Lucas-Kanade call for all boxes);
  // first_point_[i]..first_point_[i + 1] are box i's.
  const cv::Size image = latest_.image(0).size();
  const float right_edge = static_cast<float>(image.width - 1);
  const float bottom_edge = static_cast<float>(image.height - 1);
  // Room for every box's whole grid at once: boxes that move into the picture, or grow, get more
  // points without these buffers growing frame after frame (no allocation once this many boxes
  // were seen; tests/vision/box_follower_allocation_test.cpp).
  const std::size_t most_points = boxes.size() * static_cast<std::size_t>(config_.grid) *
                                  static_cast<std::size_t>(config_.grid);
  from_points_.reserve(most_points);
  to_points_.reserve(most_points);
  back_points_.reserve(most_points);
  status_.reserve(most_points);
  back_status_.reserve(most_points);
  from_points_.clear();
  first_point_.resize(boxes.size() + 1);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    first_point_[i] = static_cast<int>(from_points_.size());
    const tracker::Box& box = boxes[i];
    if (!usable(box)) continue;
    // The inner part in thumbnail pixels, cut to the image: a box partly outside the frame is
    // followed by its visible part.
    const float x0 = std::max(0.F, (box.x + kInnerLeft * box.w) * scale_);
    const float x1 = std::min(right_edge, (box.x + kInnerRight * box.w) * scale_);
    const float y0 = std::max(0.F, (box.y + kInnerTop * box.h) * scale_);
    const float y1 = std::min(bottom_edge, (box.y + kInnerBottom * box.h) * scale_);
    if (!(x1 > x0) || !(y1 > y0)) continue;
    const int columns = std::clamp(static_cast<int>((x1 - x0) / kMinSpacing), 1, config_.grid);
    const int rows = std::clamp(static_cast<int>((y1 - y0) / kMinSpacing), 1, config_.grid);
    if (columns * rows < kMinPoints) continue;
    // Cell centres: the grid's outer points stay half a cell inside the part.
    const float step_x = (x1 - x0) / static_cast<float>(columns);
    const float step_y = (y1 - y0) / static_cast<float>(rows);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c)
        from_points_.emplace_back(x0 + (static_cast<float>(c) + 0.5F) * step_x,
                                  y0 + (static_cast<float>(r) + 0.5F) * step_y);
  }
  first_point_[boxes.size()] = static_cast<int>(from_points_.size());
  if (from_points_.empty()) return;

  // Forwards, then back from where the points went (those that went somewhere: no other is
  // trusted): the round trip decides which to trust. All buffers are ours and kept: no allocation.
  const LucasKanadeConfig lk = lucas_kanade_of(config_);
  track_points(previous_, latest_, from_points_, to_points_, status_, lk, window_scratch_);
  track_points(latest_, previous_, to_points_, back_points_, back_status_, lk, window_scratch_,
               &status_);

  const float round_trip_squared = config_.max_round_trip * config_.max_round_trip;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const int first = first_point_[i];
    const int end = first_point_[i + 1];
    if (end == first) continue;
    // A point is trusted when both ways found it and it came back to where it started: an
    // occluder, a textureless patch or the aperture problem each break that.
    trusted_.clear();
    for (int p = first; p < end; ++p) {
      const cv::Point2f& to = to_points_[static_cast<std::size_t>(p)];
      const cv::Point2f round_trip =
          back_points_[static_cast<std::size_t>(p)] - from_points_[static_cast<std::size_t>(p)];
      if (status_[static_cast<std::size_t>(p)] != 0 &&
          back_status_[static_cast<std::size_t>(p)] != 0 && std::isfinite(to.x) &&
          std::isfinite(to.y) && round_trip.dot(round_trip) <= round_trip_squared)
        trusted_.push_back(p);
    }
    // Two points at least: one alone is no median (the confidence stays 0).
    if (trusted_.size() < 2) continue;

    // Medians are robust to the few trusted points on the background or on a passer-by.
    // Scale first: distances between pairs of points before and after, each point with the one
    // half the list later (far apart on the grid: their ratio is least disturbed by sub-pixel
    // noise).
    const std::size_t n = trusted_.size();
    scratch_.resize(n);
    std::size_t ratios = 0;
    const std::size_t offset = std::max<std::size_t>(1, n / 2);
    for (std::size_t t = 0; t < n; ++t) {
      const auto a = static_cast<std::size_t>(trusted_[t]);
      const auto b = static_cast<std::size_t>(trusted_[(t + offset) % n]);
      const float before = static_cast<float>(cv::norm(from_points_[a] - from_points_[b]));
      if (before < kMinPairDistance) continue;
      scratch_[ratios++] = static_cast<float>(cv::norm(to_points_[a] - to_points_[b])) / before;
    }
    const float step =
        ratios == 0 ? 1.F : std::clamp(median(scratch_, ratios), kMinScaleStep, kMaxScaleStep);
    // Then where each point says the centre went, its offset from the centre scaled by `step`:
    // a growing box's points move apart, and the plain median of their motion (the middle of an
    // even count is one of the two middle points) would drag the centre towards one side.
    const cv::Point2f centre(boxes[i].center_x() * scale_, boxes[i].center_y() * scale_);
    for (std::size_t t = 0; t < n; ++t) {
      const auto p = static_cast<std::size_t>(trusted_[t]);
      scratch_[t] = to_points_[p].x - step * (from_points_[p].x - centre.x) - centre.x;
    }
    const float dx = median(scratch_, n);
    for (std::size_t t = 0; t < n; ++t) {
      const auto p = static_cast<std::size_t>(trusted_[t]);
      scratch_[t] = to_points_[p].y - step * (from_points_[p].y - centre.y) - centre.y;
    }
    const float dy = median(scratch_, n);
    // The confidence: the share of the box's points that came back AND agree with the motion
    // found. Points on an image that changed entirely (a cut, an occluder) can each come back
    // to where they started by chance (a quarter of them did on unrelated textures), but each
    // goes its own way.
    const float agree_squared = kMaxDisagreement * kMaxDisagreement;
    int agreeing = 0;
    for (std::size_t t = 0; t < n; ++t) {
      const auto p = static_cast<std::size_t>(trusted_[t]);
      const cv::Point2f expected = centre + cv::Point2f(dx, dy) + step * (from_points_[p] - centre);
      const cv::Point2f off = to_points_[p] - expected;
      if (off.dot(off) <= agree_squared) ++agreeing;
    }
    out[i].confidence = static_cast<float>(agreeing) / static_cast<float>(end - first);
    if (out[i].confidence < config_.min_trusted) continue;

    // Around the box's centre: it moves by the points' motion and keeps its shape.
    const tracker::Box& box = boxes[i];
    const float w = box.w * step;
    const float h = box.h * step;
    const tracker::Box moved{box.center_x() + dx / scale_ - 0.5F * w,
                             box.center_y() + dy / scale_ - 0.5F * h, w, h};
    if (!usable(moved)) continue;
    out[i].box = moved;
    out[i].followed = true;
  }
}

}  // namespace rtmot::vision
