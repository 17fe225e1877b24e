#pragma once
// What a user asks of tiling (`detector.tiles`, `--tiles`): off, auto, or a grid such as 3x2
// (docs/tiling.md). `auto` is decided at start by runner/tiling_choice.hpp.
#include <optional>
#include <string>

#include "detector/tile_layout.hpp"

namespace rtmot::detector {

enum class TileMode { off, automatic, grid };

struct TileRequest {
  TileMode mode{TileMode::automatic};
  int columns{1};
  int rows{1};

  bool operator==(const TileRequest& other) const {
    return mode == other.mode && columns == other.columns && rows == other.rows;
  }
};

/// "off", "auto" or "CxR" (1 <= C, R <= kMaxTileSide; 1x1 means off). Empty and `problem` set
/// otherwise.
std::optional<TileRequest> parse_tile_request(const std::string& text, std::string& problem);

/// The request as parse_tile_request() reads it.
std::string tile_request_text(const TileRequest& request);

}  // namespace rtmot::detector
