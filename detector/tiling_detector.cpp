#include "detector/tiling_detector.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace rtmot::detector {

TilingDetector::TilingDetector(std::unique_ptr<Detector> inner, TilingConfig config)
    : inner_(std::move(inner)), config_(config), merger_(config.merge), single_(1) {
  if (!inner_) throw std::invalid_argument("TilingDetector: no detector to wrap");
}

std::vector<PixelRect> TilingDetector::plan_passes(int width, int height,
                                                   const TilingConfig& config) {
  const TileGrid grid = config.automatic
                            ? automatic_grid(width, height, config.network_size,
                                             config.max_magnification, config.grid.overlap)
                            : config.grid;
  std::vector<PixelRect> passes{{0, 0, width, height}};
  // A grid the frame is too small for leaves it whole rather than failing the run.
  if (grid.tiled() && grid.columns <= width && grid.rows <= height) {
    for (const PixelRect& tile : tile_rects(width, height, grid)) passes.push_back(tile);
  }
  return passes;
}

std::size_t TilingDetector::layout_for(int width, int height) {
  for (std::size_t i = 0; i < layouts_.size(); ++i) {
    if (layouts_[i].width == width && layouts_[i].height == height) return i;
  }
  layouts_.push_back({width, height, plan_passes(width, height, config_)});
  return layouts_.size() - 1;
}

const std::vector<PixelRect>& TilingDetector::passes_for(int width, int height) {
  return layouts_[layout_for(width, height)].passes;
}

void TilingDetector::detect(const cv::Mat& bgr_image, std::int64_t frame_number,
                            std::vector<tracker::Detection>& out) {
  const cv::Mat* image = &bgr_image;
  // A batch of one, through the same path; `out` keeps its capacity through the swaps.
  single_[0].swap(out);
  detect_batch(&image, &frame_number, 1, single_);
  single_[0].swap(out);
}

void TilingDetector::detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers,
                                  int count, std::vector<std::vector<tracker::Detection>>& out) {
  if (count < 1) throw std::invalid_argument("TilingDetector::detect_batch: count must be >= 1");
  if (out.size() < static_cast<std::size_t>(count)) out.resize(static_cast<std::size_t>(count));
  image_layouts_.clear();
  first_pass_.clear();
  std::size_t total = 0;
  for (int i = 0; i < count; ++i) {
    // Indices, not references: a new frame size grows layouts_.
    const std::size_t layout = layout_for(images[i]->cols, images[i]->rows);
    image_layouts_.push_back(layout);
    first_pass_.push_back(static_cast<int>(total));
    total += layouts_[layout].passes.size();
  }
  if (views_.size() < total) views_.resize(total);
  view_pointers_.clear();
  view_frames_.clear();
  std::size_t v = 0;
  for (int i = 0; i < count; ++i) {
    for (const PixelRect& r : layouts_[image_layouts_[static_cast<std::size_t>(i)]].passes) {
      // A header on the region: no pixel is copied (a 2-D header allocates nothing).
      views_[v] = (*images[i])(cv::Rect(r.x, r.y, r.width, r.height));
      view_pointers_.push_back(&views_[v]);
      view_frames_.push_back(frame_numbers[i]);
      ++v;
    }
  }
  inner_->detect_batch(view_pointers_.data(), view_frames_.data(), static_cast<int>(total),
                       pass_boxes_);
  // The headers hold a reference to their frames' pixels: let go of them now, so that a frame
  // buffer the pipeline hands back to its capture thread is not kept alive by a stale header.
  for (std::size_t k = 0; k < total; ++k) views_[k].release();
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
    const std::vector<PixelRect>& passes = layouts_[image_layouts_[i]].passes;
    const auto* first = &pass_boxes_[static_cast<std::size_t>(first_pass_[i])];
    if (passes.size() == 1) {  // untiled: the wrapped detector's boxes as they are
      out[i].assign(first->begin(), first->end());
    } else {
      merger_.merge(passes.data(), first, static_cast<int>(passes.size()), out[i]);
    }
  }
}

int TilingDetector::max_batch() const {
  // The most passes a frame of any size seen so far takes; before the first frame, the wrapped
  // detector's own batch (a run sizes that batch for its tiles: runner/run_detector.cpp).
  std::size_t most = 1;
  for (const Layout& layout : layouts_) most = std::max(most, layout.passes.size());
  return std::max(1, inner_->max_batch() / static_cast<int>(most));
}

std::string TilingDetector::describe() const {
  const std::string grid =
      config_.automatic ? std::string("tiles auto")
                        : fmt::format("tiles {}x{}", config_.grid.columns, config_.grid.rows);
  return fmt::format("{}, {} (overlap {:.2f}, tile score cut {:.2f}) + the whole frame",
                     inner_->describe(), grid, config_.grid.overlap,
                     config_.merge.tile_score_threshold);
}

}  // namespace rtmot::detector
