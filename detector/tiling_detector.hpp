#pragma once
// A detector that looks at a large frame in detail: the whole frame and its overlapping tiles go
// through the wrapped detector as one batch, and their boxes are merged back into frame pixels
// (docs/tiling.md). The pipeline, the engines and the batching of several cameras stay as they are:
// this is a Detector like any other.
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "detector/tile_layout.hpp"
#include "detector/tile_merge.hpp"

namespace rtmot::detector {

struct TilingConfig {
  /// The grid for every frame size, or (automatic) the one automatic_grid() gives each frame size.
  TileGrid grid;
  bool automatic{false};
  /// automatic_grid()'s parameters (a run's: runner/tiling_choice.hpp).
  int network_size{300};
  float max_magnification{2.F};
  TileMergeConfig merge;
};

/// One thread at a time, as the detector it wraps.
class TilingDetector : public Detector {
 public:
  /// Wraps `inner`, which should take a whole frame's passes in one batch (its max_batch(): a run
  /// sizes it so, runner/run_detector.cpp).
  TilingDetector(std::unique_ptr<Detector> inner, TilingConfig config);

  void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override;
  /// Every image's whole frame and tiles in one call of the wrapped detector's detect_batch.
  void detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers, int count,
                    std::vector<std::vector<tracker::Detection>>& out) override;
  /// The frames whose passes fill the wrapped detector's batch (at least 1).
  int max_batch() const override;
  std::string describe() const override;

  /// The rectangles one frame of this size is seen as: the whole frame, then its tiles.
  const std::vector<PixelRect>& passes_for(int width, int height);
  /// The passes of a frame of this size, without remembering them (for logs and auto).
  static std::vector<PixelRect> plan_passes(int width, int height, const TilingConfig& config);
  const Detector& inner() const { return *inner_; }

 private:
  /// The index in layouts_ of a frame size's passes, planned on first sight.
  std::size_t layout_for(int width, int height);

  struct Layout {
    int width;
    int height;
    std::vector<PixelRect> passes;
  };

  std::unique_ptr<Detector> inner_;
  TilingConfig config_;
  TileMerger merger_;
  std::vector<Layout> layouts_;  // one per frame size seen (cameras rarely change size)
  // Reused every call: headers on the images' regions, their frame numbers, the per-pass boxes,
  // each image's layout and where its passes start.
  std::vector<cv::Mat> views_;
  std::vector<const cv::Mat*> view_pointers_;
  std::vector<std::int64_t> view_frames_;
  std::vector<std::vector<tracker::Detection>> pass_boxes_;
  std::vector<std::size_t> image_layouts_;
  std::vector<int> first_pass_;
  std::vector<std::vector<tracker::Detection>> single_;  // detect()'s batch of one
};

}  // namespace rtmot::detector
