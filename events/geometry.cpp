#include "events/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rtmot::events {
namespace {

double cross(const Point& o, const Point& a, const Point& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

int sign(double v) {
  return (v > 0.0) - (v < 0.0);
}

bool within_box(const Point& p, const Segment& s) {
  return p.x >= std::min(s.from.x, s.to.x) && p.x <= std::max(s.from.x, s.to.x) &&
         p.y >= std::min(s.from.y, s.to.y) && p.y <= std::max(s.from.y, s.to.y);
}

Segment edge(const std::vector<Point>& polygon, std::size_t i) {
  return {polygon[i], polygon[(i + 1) % polygon.size()]};
}

}  // namespace

double Segment::length() const {
  return std::hypot(to.x - from.x, to.y - from.y);
}

double signed_distance(const Segment& s, const Point& p) {
  // cross > 0 is clockwise on a y-down image: the right of from -> to.
  return cross(s.from, s.to, p) / s.length();
}

bool crossing_position(const Segment& s, const Point& p, const Point& q, double& position) {
  const double dp = cross(s.from, s.to, p);
  const double dq = cross(s.from, s.to, q);
  if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || (dp == 0.0 && dq == 0.0)) return false;
  const double t = dp / (dp - dq);
  const Point meet{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
  const double dx = s.to.x - s.from.x;
  const double dy = s.to.y - s.from.y;
  position = ((meet.x - s.from.x) * dx + (meet.y - s.from.y) * dy) / (dx * dx + dy * dy);
  return true;
}

namespace {

PreparedEdge prepare_edge(const Segment& s) {
  const double dx = s.to.x - s.from.x;
  const double dy = s.to.y - s.from.y;
  const double squared = dx * dx + dy * dy;
  return {s.from, dx, dy, squared > 0.0 ? 1.0 / squared : 0.0};
}

double squared_distance_to_edge(const Point& p, const PreparedEdge& e) {
  double t = ((p.x - e.from.x) * e.dx + (p.y - e.from.y) * e.dy) * e.inverse_squared_length;
  // std::clamp's result. (Meant to compile to min/max instructions; g++ 12 at -O3 makes it two
  // jumps after all. A select through integer masks, without them, was measured: no gain.)
  t = t > 0.0 ? t : 0.0;
  t = t < 1.0 ? t : 1.0;
  const double ex = p.x - (e.from.x + t * e.dx);
  const double ey = p.y - (e.from.y + t * e.dy);
  return ex * ex + ey * ey;
}

}  // namespace

double distance_to_segment(const Point& p, const Segment& s) {
  return std::sqrt(squared_distance_to_edge(p, prepare_edge(s)));
}

bool segments_intersect(const Segment& a, const Segment& b) {
  const int d1 = sign(cross(b.from, b.to, a.from));
  const int d2 = sign(cross(b.from, b.to, a.to));
  const int d3 = sign(cross(a.from, a.to, b.from));
  const int d4 = sign(cross(a.from, a.to, b.to));
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && within_box(a.from, b)) || (d2 == 0 && within_box(a.to, b)) ||
         (d3 == 0 && within_box(b.from, a)) || (d4 == 0 && within_box(b.to, a));
}

bool inside_polygon(const std::vector<Point>& polygon, const Point& p) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Point& a = polygon[i];
    const Point& b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
      inside = !inside;
  }
  return inside;
}

std::vector<PreparedEdge> prepare_edges(const std::vector<Point>& polygon) {
  std::vector<PreparedEdge> edges;
  edges.reserve(polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i) edges.push_back(prepare_edge(edge(polygon, i)));
  return edges;
}

double distance_to_boundary(const std::vector<PreparedEdge>& edges, const Point& p) {
  // Squared per edge, one root at the end.
  double nearest = INFINITY;
  for (const PreparedEdge& e : edges) nearest = std::min(nearest, squared_distance_to_edge(p, e));
  return std::sqrt(nearest);
}

double distance_to_boundary_beyond(const std::vector<PreparedEdge>& edges, const Point& p,
                                   double band) {
  const double squared_band = band * band;
  double nearest = INFINITY;
  for (const PreparedEdge& e : edges) {
    const double squared = squared_distance_to_edge(p, e);
    nearest = std::min(nearest, squared);
    // The square is a cheap filter; the root decides (as distance_to_boundary()'s would).
    if (squared <= squared_band && std::sqrt(squared) <= band) return std::sqrt(squared);
  }
  return std::sqrt(nearest);
}

double distance_to_boundary(const std::vector<Point>& polygon, const Point& p) {
  return distance_to_boundary(prepare_edges(polygon), p);
}

bool move_meets_boundary(const std::vector<Point>& polygon, const Point& p, const Point& q) {
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    if (segments_intersect({p, q}, {polygon[j], polygon[i]})) return true;
  return false;
}

bool is_simple_polygon(const std::vector<Point>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return false;
  double twice_area = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Segment e = edge(polygon, i);
    if (e.length() == 0.0) return false;
    twice_area += e.from.x * e.to.y - e.to.x * e.from.y;
  }
  if (twice_area == 0.0) return false;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
      if (neighbours) {
        // Neighbours share one corner; they must not fold back onto each other.
        const Point& shared = j == i + 1 ? polygon[j] : polygon[i];
        const Point& a = j == i + 1 ? polygon[i] : polygon[j];
        const Point& b = j == i + 1 ? polygon[(j + 1) % n] : polygon[1];
        const bool collinear = cross(shared, a, b) == 0.0;
        const bool folds = collinear && ((a.x - shared.x) * (b.x - shared.x) +
                                         (a.y - shared.y) * (b.y - shared.y)) > 0.0;
        if (folds) return false;
        continue;
      }
      if (segments_intersect(edge(polygon, i), edge(polygon, j))) return false;
    }
  }
  return true;
}

}  // namespace rtmot::events
