#include "detector/tile_request.hpp"

#include <charconv>

namespace rtmot::detector {
namespace {

std::optional<int> side(const std::string& text) {
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || ptr != end || value < 1 || value > kMaxTileSide) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

std::optional<TileRequest> parse_tile_request(const std::string& text, std::string& problem) {
  if (text == "off") return TileRequest{TileMode::off, 1, 1};
  if (text == "auto") return TileRequest{TileMode::automatic, 1, 1};
  const auto x = text.find('x');
  if (x != std::string::npos) {
    const auto columns = side(text.substr(0, x));
    const auto rows = side(text.substr(x + 1));
    if (columns && rows) {
      if (*columns * *rows == 1) return TileRequest{TileMode::off, 1, 1};
      return TileRequest{TileMode::grid, *columns, *rows};
    }
  }
  problem = "expected off, auto or COLUMNSxROWS with 1.." + std::to_string(kMaxTileSide) +
            " of each (e.g. 3x2), got '" + text + "'";
  return std::nullopt;
}

std::string tile_request_text(const TileRequest& request) {
  switch (request.mode) {
    case TileMode::off:
      return "off";
    case TileMode::automatic:
      return "auto";
    case TileMode::grid:
      break;
  }
  return std::to_string(request.columns) + "x" + std::to_string(request.rows);
}

}  // namespace rtmot::detector
