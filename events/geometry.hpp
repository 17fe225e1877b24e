#pragma once
// Plane geometry of counting lines and zones, in pixels (x right, y down, the image's convention).
// Hand-written: a handful of exact formulas on doubles; a geometry library (Boost.Geometry) would
// bring a dependency the board image does not otherwise need for six functions.
#include <vector>

namespace rtmot::events {

struct Point {
  double x{0.0};
  double y{0.0};
};

struct Segment {
  Point from;
  Point to;

  double length() const;
};

/// Signed distance of `p` from the infinite line through `s`: negative on the left of from -> to as
/// seen on the image (a person at `from` looking at `to`), positive on the right, 0 on it.
double signed_distance(const Segment& s, const Point& p);

/// Where the move p -> q meets the infinite line through `s`, as the position along `s` (0 at
/// from, 1 at to); none if the move does not reach the line (both ends strictly on one side) or
/// lies on it. A move that ends on the line meets it.
bool crossing_position(const Segment& s, const Point& p, const Point& q, double& position);

double distance_to_segment(const Point& p, const Segment& s);

/// True when the closed segments share a point (touching counts).
bool segments_intersect(const Segment& a, const Segment& b);

/// Even-odd rule, so concave polygons are right. A point on the boundary may go either way; the
/// zone logic never decides on it (the dead band).
bool inside_polygon(const std::vector<Point>& polygon, const Point& p);

double distance_to_boundary(const std::vector<Point>& polygon, const Point& p);

/// An edge with what the distance to it needs prepared: the counter asks the distance to a zone's
/// border of every track near it, and a division per edge was most of that.
struct PreparedEdge {
  Point from;
  double dx{0.0};
  double dy{0.0};
  double inverse_squared_length{0.0};  // 0 for a zero-length edge
};
std::vector<PreparedEdge> prepare_edges(const std::vector<Point>& polygon);
double distance_to_boundary(const std::vector<PreparedEdge>& edges, const Point& p);
/// distance_to_boundary() where it is more than `band`; otherwise some value of at most `band`,
/// found at the first edge within it: a caller that only compares with the band learns the
/// same, and a point near the border (half of those the counter asks about) skips the rest.
double distance_to_boundary_beyond(const std::vector<PreparedEdge>& edges, const Point& p,
                                   double band);

/// True when the move p -> q meets any edge of the polygon.
bool move_meets_boundary(const std::vector<Point>& polygon, const Point& p, const Point& q);

/// A simple polygon: no edge meets another except its two neighbours at their shared corner, no
/// zero-length edge, nonzero area. Returns false for fewer than 3 points.
bool is_simple_polygon(const std::vector<Point>& polygon);

}  // namespace rtmot::events
