#pragma once
// Where a large frame is cut into overlapping tiles, each seen by the network at about its own
// input size, so that a person far from the camera is not squeezed below the SSD's smallest anchor
// (docs/tiling.md). Pure geometry: no image is touched here.
#include <vector>

namespace rtmot::detector {

/// The most columns or rows a grid may have: 8 x 8 tiles are 65 passes of the network a frame,
/// past anything that pays (docs/tiling.md).
constexpr int kMaxTileSide = 8;

/// A rectangle of a frame, in whole pixels.
struct PixelRect {
  int x{0};
  int y{0};
  int width{0};
  int height{0};

  int right() const { return x + width; }
  int bottom() const { return y + height; }
  bool operator==(const PixelRect& other) const {
    return x == other.x && y == other.y && width == other.width && height == other.height;
  }
};

/// A grid of `columns` x `rows` tiles; neighbours share `overlap` of a tile's width (height).
/// 1 x 1 is no tiling.
struct TileGrid {
  int columns{1};
  int rows{1};
  float overlap{0.2F};

  bool tiled() const { return columns * rows > 1; }
  bool operator==(const TileGrid& other) const {
    return columns == other.columns && rows == other.rows && overlap == other.overlap;
  }
};

/// The grid's tiles of a `width` x `height` frame, row by row; together they cover the frame
/// exactly (the last column and row end at its edges). Throws std::invalid_argument for a grid or
/// frame that cannot be cut so (a tile under 1 pixel, overlap outside [0, 0.9]).
std::vector<PixelRect> tile_rects(int width, int height, const TileGrid& grid);

/// The grid `auto` chooses for a frame seen by a `network_size` x `network_size` network: rows so
/// that a tile is at most `max_magnification` x the network's size tall, and at least two as soon
/// as a tile of two rows is no smaller than the network's input (nothing is magnified); as many
/// columns as keep the tiles near square (the SSD was trained on photos squeezed to a square, and a
/// square tile keeps people's shape); at most kMaxTileSide of each. 1 x 1 when the frame is smaller
/// than two rows of network-sized tiles.
TileGrid automatic_grid(int width, int height, int network_size, float max_magnification,
                        float overlap);

}  // namespace rtmot::detector
