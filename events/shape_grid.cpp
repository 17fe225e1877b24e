#include "events/shape_grid.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::events {
namespace {

// At most this many cells (16 bytes each: 128 KiB), none smaller than kMinCell pixels.
constexpr double kMaxCells = 8192.0;
constexpr double kMinCell = 8.0;
// A shape within this many cell sizes of a cell is one of its candidates. Farther ones bound the
// cell's clearance, which decides how often a track in the open is looked at again; nearer ones
// are computed at every look.
constexpr double kCandidateCells = 2.0;

// Rounds down to a float: a lower bound stays one.
float float_below(double value) {
  float f = static_cast<float>(value);
  if (static_cast<double>(f) > value) f = std::nextafter(f, -INFINITY);
  return f;
}

}  // namespace

ShapeGrid::ShapeGrid(const EventsConfig& config) {
  const std::size_t shapes = config.lines.size() + config.zones.size();
  if (shapes == 0 || shapes > kMaxShapes) return;
  double min_x = INFINITY;
  double min_y = INFINITY;
  double max_x = -INFINITY;
  double max_y = -INFINITY;
  const auto extend = [&](const Point& p) {
    min_x = std::min(min_x, p.x);
    min_y = std::min(min_y, p.y);
    max_x = std::max(max_x, p.x);
    max_y = std::max(max_y, p.y);
  };
  for (const LineSpec& line : config.lines) {
    extend(line.segment.from);
    extend(line.segment.to);
  }
  for (const ZoneSpec& zone : config.zones)
    for (const Point& p : zone.polygon) extend(p);
  if (!std::isfinite(min_x) || !std::isfinite(min_y) || !std::isfinite(max_x) ||
      !std::isfinite(max_y))
    return;
  // The shapes' extent and a margin of the candidate reach and a cell: off the grid, a track's
  // every shape is computed (correct anywhere, only slower).
  const double width = max_x - min_x;
  const double height = max_y - min_y;
  const double margin_cells = kCandidateCells + 1.0;
  double cell = std::max(kMinCell, std::sqrt(width * height / kMaxCells));
  while ((width / cell + 2.0 * margin_cells + 1.0) * (height / cell + 2.0 * margin_cells + 1.0) >
         kMaxCells)
    cell *= 1.25;
  columns_ = std::ceil(width / cell + 2.0 * margin_cells);
  rows_ = std::ceil(height / cell + 2.0 * margin_cells);
  x0_ = min_x - margin_cells * cell;
  y0_ = min_y - margin_cells * cell;
  inverse_cell_ = 1.0 / cell;

  const std::size_t lines = config.lines.size();
  std::vector<std::vector<PreparedEdge>> edges;
  for (const ZoneSpec& zone : config.zones) edges.push_back(prepare_edges(zone.polygon));
  const auto cells = static_cast<std::size_t>(columns_ * rows_);
  cells_.assign(cells, Cell{});
  const double reach = kCandidateCells * cell;
  for (std::size_t row = 0; row < static_cast<std::size_t>(rows_); ++row) {
    for (std::size_t column = 0; column < static_cast<std::size_t>(columns_); ++column) {
      const Point centre{x0_ + (static_cast<double>(column) + 0.5) * cell,
                         y0_ + (static_cast<double>(row) + 0.5) * cell};
      // Rounding of the counter's own formulas (other operations on the same numbers) is far
      // below this.
      const double slack = 1e-6 + 1e-9 * (std::abs(centre.x) + std::abs(centre.y) + cell);
      const std::size_t index = row * static_cast<std::size_t>(columns_) + column;
      double far = INFINITY;
      for (std::size_t k = 0; k < shapes; ++k) {
        double bound = 0.0;
        if (k < lines) {
          // The line's distance changes by at most |n.x| + |n.y| times half a cell from the centre
          // (n the unit normal).
          const Segment& s = config.lines[k].segment;
          const double length = s.length();
          const double half_width =
              0.5 * cell * (std::abs(s.to.x - s.from.x) + std::abs(s.to.y - s.from.y)) / length;
          bound = std::abs(signed_distance(s, centre)) - half_width;
        } else {
          bound = distance_to_boundary(edges[k - lines], centre) - cell * std::sqrt(0.5);
        }
        bound -= slack;
        if (bound <= reach) {
          cells_[index].candidates |= std::uint64_t{1} << k;
        } else {
          far = std::min(far, bound);
        }
      }
      cells_[index].clearance = float_below(far);
    }
  }
}

}  // namespace rtmot::events
