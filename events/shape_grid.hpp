#pragma once
// Which lines and zones a track can be near, looked up by where it is: a grid over the shapes,
// worked out once at configuration. Each cell lists the shapes that come within a few cells of
// it (its candidates) and a lower bound of the distance from anywhere in the cell to every other
// shape. A counter that looks at a track's shapes then computes only its cell's candidates
// exactly; the others are known to be at least that far. Distances are the counter's: to a
// line's infinite line (its sides), to a zone's border.
#include <cmath>
#include <cstdint>
#include <vector>

#include "events/events_config.hpp"

namespace rtmot::events {

class ShapeGrid {
 public:
  /// A cell's candidates are a bit set of shape indices (lines first, then zones).
  static constexpr std::size_t kMaxShapes = 64;
  static constexpr std::uint32_t kOutside = ~std::uint32_t{0};

  /// Off (every point outside) with no shapes or more than kMaxShapes.
  explicit ShapeGrid(const EventsConfig& config);

  bool enabled() const { return !cells_.empty(); }

  /// The cell of `p`, or kOutside (off the grid, or not a finite point).
  std::uint32_t cell_of(const Point& p) const {
    const double fx = (p.x - x0_) * inverse_cell_;
    const double fy = (p.y - y0_) * inverse_cell_;
    if (!(fx >= 0.0 && fx < columns_ && fy >= 0.0 && fy < rows_)) return kOutside;
    return static_cast<std::uint32_t>(fy) * static_cast<std::uint32_t>(columns_) +
           static_cast<std::uint32_t>(fx);
  }
  struct Cell {
    std::uint64_t candidates{0};
    /// No point of the cell is nearer than this to any shape not among its candidates
    /// (INFINITY: every shape is a candidate). Rounded down to a float: still a bound.
    float clearance{INFINITY};
  };
  /// One load for both: the cell is read when a track is looked at, most often from L2.
  const Cell& cell(std::uint32_t index) const { return cells_[index]; }

 private:
  double x0_{0.0};
  double y0_{0.0};
  double inverse_cell_{0.0};
  double columns_{0.0};
  double rows_{0.0};
  std::vector<Cell> cells_;
};

}  // namespace rtmot::events
