#include "detector/tile_layout.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rtmot::detector {
namespace {

// `count` spans of `length` pixels along an axis of `total`, neighbours sharing `overlap` of a
// span: length = total / (count - (count - 1) * overlap). Starts are rounded, the last span ends at
// the edge.
void cut_axis(int total, int count, float overlap, std::vector<int>& starts, int& length) {
  const double span =
      static_cast<double>(total) / (count - (count - 1) * static_cast<double>(overlap));
  length = std::min(total, static_cast<int>(std::ceil(span)));
  starts.clear();
  for (int i = 0; i < count; ++i) {
    const int start =
        i + 1 == count ? total - length : static_cast<int>(std::lround(i * span * (1.0 - overlap)));
    starts.push_back(std::clamp(start, 0, total - length));
  }
}

}  // namespace

std::vector<PixelRect> tile_rects(int width, int height, const TileGrid& grid) {
  if (width < 1 || height < 1) throw std::invalid_argument("tile_rects: empty frame");
  if (grid.columns < 1 || grid.rows < 1 || grid.columns > width || grid.rows > height) {
    throw std::invalid_argument("tile_rects: a " + std::to_string(grid.columns) + "x" +
                                std::to_string(grid.rows) + " grid does not fit a " +
                                std::to_string(width) + "x" + std::to_string(height) + " frame");
  }
  if (!(grid.overlap >= 0.F && grid.overlap <= 0.9F)) {
    throw std::invalid_argument("tile_rects: overlap outside [0, 0.9]");
  }
  std::vector<int> xs;
  std::vector<int> ys;
  int tile_width = 0;
  int tile_height = 0;
  cut_axis(width, grid.columns, grid.overlap, xs, tile_width);
  cut_axis(height, grid.rows, grid.overlap, ys, tile_height);
  std::vector<PixelRect> tiles;
  tiles.reserve(xs.size() * ys.size());
  for (const int y : ys) {
    for (const int x : xs) tiles.push_back({x, y, tile_width, tile_height});
  }
  return tiles;
}

TileGrid automatic_grid(int width, int height, int network_size, float max_magnification,
                        float overlap) {
  TileGrid grid;
  grid.overlap = overlap;
  const auto tile_height = [&](int rows) {
    return height / (rows - (rows - 1) * static_cast<double>(overlap));
  };
  if (tile_height(2) < network_size - 0.5) return grid;  // two rows would magnify: seen whole
  grid.rows = 2;
  // Half a pixel of slack: 0.2F is not 0.2, and 1080 rows in two tiles are 600, not 600.00001.
  const double tallest = static_cast<double>(network_size) * max_magnification + 0.5;
  while (grid.rows < kMaxTileSide && tile_height(grid.rows) > tallest) {
    ++grid.rows;
  }
  // Columns whose tiles come closest to square.
  const double ideal_columns = (width / tile_height(grid.rows) - overlap) / (1.0 - overlap);
  grid.columns = std::clamp(static_cast<int>(std::lround(ideal_columns)), 1, kMaxTileSide);
  return grid;
}

}  // namespace rtmot::detector
