#include "detector/tile_merge.hpp"

#include <algorithm>
#include <cstddef>

#include "tracker/box_geometry.hpp"

namespace rtmot::detector {
namespace {

enum CutSide : int { kLeft = 1, kTop = 2, kRight = 4, kBottom = 8 };

float interval_overlap(float a0, float a1, float b0, float b1) {
  return std::max(0.F, std::min(a1, b1) - std::max(a0, b0));
}

// Intersection over the union of two intervals.
float interval_iou(float a0, float a1, float b0, float b1) {
  const float inter = interval_overlap(a0, a1, b0, b1);
  const float uni = std::max(a1, b1) - std::min(a0, b0);
  return uni > 0.F ? inter / uni : 0.F;
}

// How much of `inner` lies inside `outer`.
float inside_fraction(const tracker::Box& inner, const tracker::Box& outer) {
  const float area = inner.area();
  if (area <= 0.F) return 0.F;
  return interval_overlap(inner.x, inner.x + inner.w, outer.x, outer.x + outer.w) *
         interval_overlap(inner.y, inner.y + inner.h, outer.y, outer.y + outer.h) / area;
}

// Two halves of one object cut by the shared edge of two tiles: one cut on the facing side of the
// other, their extents across the cut alike, and meeting along it (the tiles overlap).
constexpr float kHalvesAlike = 0.6F;

bool halves_of_one(const tracker::Box& a, int a_cut, const tracker::Box& b, int b_cut) {
  const bool side_by_side =
      ((a_cut & kRight) && (b_cut & kLeft)) || ((a_cut & kLeft) && (b_cut & kRight));
  if (side_by_side && interval_iou(a.y, a.y + a.h, b.y, b.y + b.h) >= kHalvesAlike &&
      interval_overlap(a.x, a.x + a.w, b.x, b.x + b.w) > 0.F) {
    return true;
  }
  const bool stacked =
      ((a_cut & kBottom) && (b_cut & kTop)) || ((a_cut & kTop) && (b_cut & kBottom));
  return stacked && interval_iou(a.x, a.x + a.w, b.x, b.x + b.w) >= kHalvesAlike &&
         interval_overlap(a.y, a.y + a.h, b.y, b.y + b.h) > 0.F;
}

tracker::Box union_box(const tracker::Box& a, const tracker::Box& b) {
  const float x1 = std::min(a.x, b.x);
  const float y1 = std::min(a.y, b.y);
  const float x2 = std::max(a.x + a.w, b.x + b.w);
  const float y2 = std::max(a.y + a.h, b.y + b.h);
  return {x1, y1, x2 - x1, y2 - y1};
}

}  // namespace

void TileMerger::merge(const PixelRect* rects, const std::vector<tracker::Detection>* passes,
                       int count, std::vector<tracker::Detection>& out) {
  out.clear();
  collect(rects, passes, count);
  join_cut_halves();
  suppress(out);
}

void TileMerger::collect(const PixelRect* rects, const std::vector<tracker::Detection>* passes,
                         int count) {
  candidates_.clear();
  if (count < 1) return;
  const PixelRect& frame = rects[0];
  for (int pass = 0; pass < count; ++pass) {
    const PixelRect& tile = rects[pass];
    const bool whole = pass == 0;
    const float margin_x = config_.edge_margin * static_cast<float>(tile.width);
    const float margin_y = config_.edge_margin * static_cast<float>(tile.height);
    for (const tracker::Detection& d : passes[pass]) {
      if (!whole && (d.score < config_.tile_score_threshold ||
                     d.box.h > config_.tile_max_height * static_cast<float>(tile.height))) {
        continue;
      }
      int cut = 0;
      if (!whole) {
        if (tile.x > frame.x && d.box.x <= margin_x) cut |= kLeft;
        if (tile.y > frame.y && d.box.y <= margin_y) cut |= kTop;
        if (tile.right() < frame.right() && d.box.x + d.box.w >= tile.width - margin_x)
          cut |= kRight;
        if (tile.bottom() < frame.bottom() && d.box.y + d.box.h >= tile.height - margin_y)
          cut |= kBottom;
      }
      const tracker::Box in_frame{d.box.x + static_cast<float>(tile.x),
                                  d.box.y + static_cast<float>(tile.y), d.box.w, d.box.h};
      candidates_.push_back({in_frame, d.score, d.class_id, pass, cut});
    }
  }
}

void TileMerger::join_cut_halves() {
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    Candidate& a = candidates_[i];
    if (a.cut_sides == 0) continue;
    for (std::size_t j = i + 1; j < candidates_.size(); ++j) {
      Candidate& b = candidates_[j];
      if (b.cut_sides == 0 || b.pass == a.pass || b.class_id != a.class_id ||
          !halves_of_one(a.box, a.cut_sides, b.box, b.cut_sides)) {
        continue;
      }
      a.box = union_box(a.box, b.box);
      a.score = std::max(a.score, b.score);
      a.cut_sides = 0;
      b.class_id = -1;  // taken into a
      break;
    }
  }
  candidates_.erase(std::remove_if(candidates_.begin(), candidates_.end(),
                                   [](const Candidate& c) { return c.class_id < 0; }),
                    candidates_.end());
}

void TileMerger::suppress(std::vector<tracker::Detection>& out) {
  // Whole boxes before cut ones (a cut box is a part of something), best score first.
  std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
    const bool a_cut = a.cut_sides != 0;
    const bool b_cut = b.cut_sides != 0;
    if (a_cut != b_cut) return b_cut;
    return a.score > b.score;
  });
  kept_.clear();
  for (const Candidate& c : candidates_) {
    const bool duplicate = std::any_of(kept_.begin(), kept_.end(), [&](const Candidate& k) {
      if (k.class_id != c.class_id || k.pass == c.pass) return false;  // the SSD's NMS chose there
      return tracker::iou(k.box, c.box) > config_.nms_iou ||
             inside_fraction(c.box, k.box) > config_.containment;
    });
    if (!duplicate) kept_.push_back(c);
  }
  std::sort(kept_.begin(), kept_.end(),
            [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  for (const Candidate& k : kept_) out.push_back({k.box, k.score, k.class_id});
}

}  // namespace rtmot::detector
