#pragma once
// The boxes of one frame seen as several passes (the whole frame, then overlapping tiles of it)
// become one set of boxes in frame pixels (docs/tiling.md, "Merging"). Within a pass the SSD's own
// NMS already chose; across passes the same person appears more than once: whole in one pass, whole
// or cut by a tile's edge in another. Allocation-free once its buffers have grown.
#include <vector>

#include "detector/tile_layout.hpp"
#include "tracker/box.hpp"

namespace rtmot::detector {

struct TileMergeConfig {
  /// A tile pass's own score cut (the whole frame keeps the detector's): a tile magnifies texture,
  /// and its low-scoring boxes are mostly not people. 0.4 was chosen from 0.3, 0.4, 0.5 on the
  /// first halves of the in-sample videos (docs/tiling.md, "How the settings were chosen").
  float tile_score_threshold{0.4F};
  /// Across passes, a box overlapping a better one of its class by more than this IoU is the same
  /// object.
  float nms_iou{0.5F};
  /// Across passes, a box lying this much inside a better one of its class (intersection over its
  /// own area) is a part of that object seen in a tile. Chosen from 0.5, 0.6, 0.7, 0.9 as the
  /// tile cut was.
  float containment{0.6F};
  /// A tile's box whose edge lies within this fraction of the tile's size from an edge the tile
  /// shares with its neighbours (not the frame's) is cut by the tile.
  float edge_margin{0.02F};
  /// A tile reports only boxes below this fraction of its height: a taller one is a large object
  /// that the whole-frame pass sees whole.
  float tile_max_height{0.9F};
};

class TileMerger {
 public:
  explicit TileMerger(TileMergeConfig config) : config_(config) {}

  /// `passes[i]` holds the boxes found in the frame's rectangle `rects[i]` (pass 0: the whole
  /// frame), in that rectangle's pixels. Fills `out` (cleared) with the merged boxes in frame
  /// pixels, best score first.
  void merge(const PixelRect* rects, const std::vector<tracker::Detection>* passes, int count,
             std::vector<tracker::Detection>& out);

  const TileMergeConfig& config() const { return config_; }

 private:
  struct Candidate {
    tracker::Box box;  // frame pixels
    float score;
    int class_id;
    int pass;
    int cut_sides;  // CutSide bits: the edges it touches that its tile shares with a neighbour
  };

  void collect(const PixelRect* rects, const std::vector<tracker::Detection>* passes, int count);
  void join_cut_halves();
  void suppress(std::vector<tracker::Detection>& out);

  TileMergeConfig config_;
  std::vector<Candidate> candidates_;
  std::vector<Candidate> kept_;
};

}  // namespace rtmot::detector
