#include "events/event_counter.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rtmot::events {
namespace {

// Enough anchor offsets for a stable median, few enough to follow a change of scene in seconds.
constexpr std::size_t kNoiseWindow = 256;
// The median of the window redone every this many reports once the window is full: with 50
// tracks, every 41 frames (1.6 s at 25 fps). A median of 512 values moves slowly, and an
// nth_element over them every 5 frames (the tracker's 256) was a quarter of the counter's time.
constexpr std::int64_t kNoiseSnapshotGap = 2048;
// Reports this many frame periods apart or less are neighbouring frames (timestamps wobble).
// The farthest a track's disc is moved from `to` (place_disc()): far enough to be a half plane
// near the track, near enough for the rounding of its centre (about 1e-12 px) to stay far below
// kDiscRounding, which its radius is made smaller by.
constexpr double kMaxDiscShift = 4096.0;
constexpr double kDiscRounding = 1e-6;
constexpr double kNeighbourGap = 1.5;

// True when `from` is nearer to `to` than `radius`: with `radius` the distance of `to` from a
// zone's border, the move from -> to lies in a disc that holds no point of the border and cannot
// meet it. (A move that meets the border from outside, with `from` beyond the band, is longer than
// that distance plus the band: the margin is the band, far above rounding.) It spares most moves
// the eight segment tests of move_meets_boundary(): they are a few pixels, the distances more.
bool within(const Point& from, const Point& to, double radius) {
  const double dx = to.x - from.x;
  const double dy = to.y - from.y;
  return dx * dx + dy * dy < radius * radius;
}

// A bound below `earliest + threshold` by more than the rounding of `time - earliest`: before it
// no visit is due (the exact test is `time - earliest >= threshold`).
double due_from(double earliest, double threshold) {
  return earliest + threshold - 1e-9 * (std::abs(earliest) + threshold + 1.0);
}

}  // namespace

EventCounter::EventCounter(EventsConfig config)
    : config_(std::move(config)), grid_(config_), noise_window_(kNoiseWindow, kNoiseSnapshotGap) {
  const auto tracks = static_cast<std::size_t>(std::max(config_.max_tracks, 1));
  slots_.resize(tracks);
  line_states_.resize(tracks * config_.lines.size());
  zone_states_.resize(tracks * config_.zones.size());
  // An update decides at most one crossing per track and line, and per track and zone an enter
  // and an exit (a move through it) plus one dwell: the list never grows past this.
  events_.reserve(tracks * (config_.lines.size() + 3 * config_.zones.size()));
  line_counts_.resize(config_.lines.size());
  for (const LineSpec& line : config_.lines) {
    const double dx = line.segment.to.x - line.segment.from.x;
    const double dy = line.segment.to.y - line.segment.from.y;
    const double squared = dx * dx + dy * dy;
    lines_.push_back({line.segment.from, dx, dy, 1.0 / std::sqrt(squared), 1.0 / squared});
  }
  for (const ZoneSpec& zone : config_.zones) {
    Bounds bounds{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const Point& p : zone.polygon) {
      bounds.min_x = std::min(bounds.min_x, p.x);
      bounds.min_y = std::min(bounds.min_y, p.y);
      bounds.max_x = std::max(bounds.max_x, p.x);
      bounds.max_y = std::max(bounds.max_y, p.y);
    }
    zone_bounds_.push_back(bounds);
    zone_edges_.push_back(prepare_edges(zone.polygon));
  }
  zone_counts_.resize(config_.zones.size());
  earliest_pending_.assign(config_.zones.size(), INFINITY);
  live_.reserve(tracks);
  births_.reserve(tracks);
  hints_.assign(tracks, kNone);
  free_.reserve(tracks);
  for (std::size_t i = tracks; i > 0; --i) free_.push_back(static_cast<std::uint32_t>(i - 1));
}

Point EventCounter::anchor_of(const tracker::Box& box) const {
  return anchor_at(box, config_.anchor == Anchor::bottom_centre);
}

std::uint32_t EventCounter::find_live(std::int32_t track_id) const {
  for (const std::uint32_t index : live_)
    if (slots_[index].track_id == track_id) return index;
  return kNone;
}

// Inline into update(): it runs for every report, and most of the time it is a few loads, one
// comparison and a few stores (the call's register saves were a sizable part of that).
inline void EventCounter::follow(std::uint32_t index, const tracker::TrackReport& report,
                                 double time, const PerUpdate& now) {
  Slot& slot = slots_[index];
  const Point to = anchor_at(report.box, now.bottom_centre);
  const bool first = slot.last_update < 0;
  if (now.measuring_noise) measure_noise(slot, report.box, time);
  const double band = std::max(now.min_band, now.noise_factor * box_noise_ * report.box.h);
  slot.class_id = report.class_id;
  const Point from = first ? to : slot.anchor;
  // The clearance: when the shapes were last looked at, from `look`, no line and no zone border
  // was nearer than `clearance` (0 when the track was within a band). While the track stays
  // closer to `look` than the clearance minus today's band, its positions since, and the straight
  // moves between them, lie in a disc that meets no shape, and it is beyond the band on the same
  // side of each: looking would decide nothing, so it is skipped. Displacement, not path length:
  // a person walking to and fro beside a line, or a box jittering in place, is never looked at.
  // Most tracks are far from every shape most of the time: most updates cost this comparison.
  const double dx = to.x - slot.look.x;
  const double dy = to.y - slot.look.y;
  const double room = slot.clearance - band;
  if (first || !(room > 0.0 && dx * dx + dy * dy < room * room))
    look(index, from, to, band, first, time);
  slot.previous_size = first ? Size{report.box.w, report.box.h} : slot.size;
  slot.size = {report.box.w, report.box.h};
  slot.previous_update = slot.last_update;
  slot.anchor = to;
  slot.last_update = now.update;
  slot.previous_seen = slot.last_seen;
  slot.last_seen = time;
}

const std::vector<Event>& EventCounter::update(const std::vector<tracker::TrackReport>& reports,
                                               double time_seconds) {
  events_.clear();
  births_.clear();
  // The box noise is measured only in the updates whose values can be in the window when its
  // median is next redone: the window holds kNoiseWindow values and the median is redone every
  // kNoiseSnapshotGap reports; in between the reports are only counted (measuring every track
  // of every update was a third of the counter's time).
  // What every report reads, read once: across the stores into a slot and the calls of look()
  // the compiler reloaded each member, and divided by the slot size for slots_.size(), for every
  // report (a third of the instructions per report).
  const PerUpdate now{noise_window_.keeps_next(), config_.anchor == Anchor::bottom_centre,
                      config_.dead_band.min_px, config_.dead_band.noise_factor, updates_};
  const bool every_class = config_.classes.empty();
  const double lost_after = config_.lost_after_seconds;
  const std::size_t report_count = reports.size();
  const std::size_t hint_count = hints_.size();
  const std::size_t slot_count = slots_.size();
  std::int64_t followed = 0;
  // Known tracks first, so that a track born now can only take over one that was not reported.
  for (std::size_t r = 0; r < report_count; ++r) {
    const tracker::TrackReport& report = reports[r];
    if (!every_class && !counts_class(report.class_id)) continue;
    // A tracker reports its tracks in the same order update after update: the slot that held the
    // report at this position last time is nearly always the one. Otherwise a scan of the live.
    std::uint32_t index = r < hint_count ? hints_[r] : kNone;
    if (!(index < slot_count && slots_[index].live && slots_[index].track_id == report.id))
      index = find_live(report.id);
    if (index != kNone && time_seconds - slots_[index].last_seen > lost_after) {
      forget(index, time_seconds);  // gone too long: this is a new life under the same id
      index = kNone;
    }
    if (index == kNone) {
      if (births_.size() == births_.capacity()) {
        ++tracks_not_followed_;  // more births at once than tracks followed: never allocate
      } else {
        births_.push_back(static_cast<std::uint32_t>(r));
      }
      continue;
    }
    if (r < hint_count) hints_[r] = index;
    follow(index, report, time_seconds, now);
    ++followed;
  }
  for (const std::uint32_t r : births_) {
    const tracker::TrackReport& report = reports[r];
    std::uint32_t index = find_broken_off(report, time_seconds);
    if (index != kNone) {
      slots_[index].track_id = report.id;  // the same person under a new id: its state goes on
    } else {
      if (free_.empty()) {
        ++tracks_not_followed_;
        continue;
      }
      index = free_.back();
      free_.pop_back();
      live_.push_back(index);
      slots_[index] = Slot{};
      slots_[index].track_id = report.id;
      slots_[index].live = true;
      oldest_seen_ = std::min(oldest_seen_, time_seconds);
      for (std::size_t l = 0; l < config_.lines.size(); ++l) line_state(index, l) = LineState{};
      for (std::size_t z = 0; z < config_.zones.size(); ++z) zone_state(index, z) = ZoneState{};
    }
    if (r < hint_count) hints_[r] = index;
    follow(index, report, time_seconds, now);
    ++followed;
  }
  // Tracks unseen too long are gone. A scan of every live track per update would cost as much as
  // following them; the oldest sighting is a bound that says when one can be due.
  if (time_seconds - oldest_seen_ > config_.lost_after_seconds) {
    oldest_seen_ = INFINITY;
    for (std::size_t i = live_.size(); i > 0; --i) {
      const std::uint32_t index = live_[i - 1];
      if (time_seconds - slots_[index].last_seen > config_.lost_after_seconds) {
        forget(index, time_seconds);
      } else {
        oldest_seen_ = std::min(oldest_seen_, slots_[index].last_seen);
      }
    }
  }
  if (!now.measuring_noise) {
    noise_window_.pass(followed);
    settle_noise();
  }
  dwell(time_seconds);
  ++updates_;
  return events_;
}

std::uint32_t EventCounter::find_broken_off(const tracker::TrackReport& report, double time) const {
  // A tracker that loses a person for a while often finds them again under a new id: the first
  // track dies before the line, the second is born after it with no known side, and the crossing
  // is lost. A birth close to where a track not reported now was last seen, with a similar size,
  // continues that track's state. Nearest first; each such track continues one birth only.
  if (!(config_.link_radius > 0.0)) return kNone;
  const Point anchor = anchor_of(report.box);
  const double h = report.box.h;
  std::uint32_t best = kNone;
  double best_distance = config_.link_radius * h;
  for (const std::uint32_t index : live_) {
    const Slot& slot = slots_[index];
    if (slot.last_update == updates_ || time - slot.last_seen > config_.lost_after_seconds)
      continue;
    if (!(slot.size.h > 0.0) || h > 1.5 * slot.size.h || slot.size.h > 1.5 * h) continue;
    const double distance = std::hypot(anchor.x - slot.anchor.x, anchor.y - slot.anchor.y);
    if (distance <= best_distance) {
      best_distance = distance;
      best = index;
    }
  }
  return best;
}

const std::vector<Event>& EventCounter::finish(double time_seconds) {
  events_.clear();
  dwell(time_seconds);
  while (!live_.empty()) forget(live_.back(), time_seconds);
  return events_;
}

void EventCounter::measure_noise(const Slot& slot, const tracker::Box& box, double time) {
  // The box's size, not its position: between processed frames a person (or the camera) moves
  // far, but the size changes smoothly, so what its second difference shows is the detector's
  // jitter, the same that moves the anchor. Three sizes from consecutive updates only, and with
  // a known frame period only from neighbouring frames: over frames far apart the size truly
  // changes, and the measure would grow with the gap while the jitter does not.
  const double period = config_.frame_period_seconds;
  const double w = box.w;
  const double h = box.h;
  const bool measurable =
      slot.last_update == updates_ - 1 && slot.previous_update == updates_ - 2 &&
      !(period > 0.0 && (time - slot.last_seen > kNeighbourGap * period ||
                         slot.last_seen - slot.previous_seen > kNeighbourGap * period)) &&
      w > 0.0 && h > 0.0;
  // (|ddw| / w + |ddh| / h) / 2 with one division.
  const double residual = measurable
                              ? (std::abs(w - 2.0 * slot.size.w + slot.previous_size.w) * h +
                                 std::abs(h - 2.0 * slot.size.h + slot.previous_size.h) * w) /
                                    (2.0 * w * h)
                              : NAN;
  if (std::isfinite(residual)) {  // sizes out of a file may be anything
    noise_window_.push(static_cast<float>(residual));
    ++noise_values_;
  } else {
    noise_window_.pass();  // every report followed counts in the schedule
  }
  settle_noise();
}

void EventCounter::settle_noise() {
  if (!noise_window_.due()) return;
  noise_window_.snapshot();
  // Every value pushed is a finite (|ddw| h + |ddh| w) / (2 w h) with w, h > 0: +0 or more.
  if (noise_values_ > 0) box_noise_ = noise_window_.order_statistic_of_nonnegative(0.5);
}

inline double EventCounter::look_at_line(std::uint32_t index, std::size_t l, const Point& from,
                                         const Point& to, double band, bool first, double time) {
  const Slot& slot = slots_[index];
  LineState& state = line_state(index, l);
  const PreparedLine& line = lines_[l];
  // signed_distance() and crossing_position() of geometry.hpp, with the line's constants
  // prepared and the previous position's distance remembered: one cross product per line and
  // update, the crossing point only when the move changes sides.
  const auto distance_of = [&line](const Point& p) {
    return (line.dx * (p.y - line.from.y) - line.dy * (p.x - line.from.x)) * line.inverse_length;
  };
  const double distance = distance_of(to);
  if (!first) {
    // The distance kept is `from`'s if this line was looked at in the track's last update.
    const double previous =
        state.looked_at == slot.last_update ? state.distance : distance_of(from);
    const bool meets = (previous <= 0.0 && distance >= 0.0) || (previous >= 0.0 && distance <= 0.0);
    if (meets && !(previous == 0.0 && distance == 0.0)) {
      const double t = previous / (previous - distance);
      const double mx = from.x + t * (to.x - from.x) - line.from.x;
      const double my = from.y + t * (to.y - from.y) - line.from.y;
      const double position = (mx * line.dx + my * line.dy) * line.inverse_squared_length;
      if (position >= 0.0 && position <= 1.0) state.met_within_ends = true;
    }
  }
  state.distance = distance;
  state.looked_at = updates_;
  const std::int8_t side = distance > band ? 1 : distance < -band ? -1 : 0;
  if (side == 0) return 0.0;  // in the dead band: keeps the side it had
  if (state.side != 0 && side != state.side && state.met_within_ends)
    count_crossing(l, slot, side, to, time);
  state.side = side;
  state.met_within_ends = false;
  return std::abs(distance);
}

inline void EventCounter::place_disc(Slot& slot, std::uint32_t index, const Point& to,
                                     double clearance, double others, double nearest,
                                     std::size_t nearest_shape) {
  slot.look = to;
  slot.clearance = clearance;
  // A track near a line is most often near that line alone, walking to it or away from it. A
  // disc around `to` of the line's distance would have it looked at again each time it has gone
  // that distance less the band: a dozen looks as it walks away from a line it crossed, the
  // distance left doubling each time. The disc moved away from the line by `shift`, its radius
  // grown by as much, is as far from the line; it stays clear of every other shape while its
  // radius is at most their clearance from `to` less the shift (triangle inequality); and it
  // holds the disc around `to`: looked at again as soon as before when walking to the line, far
  // later when walking along or away. The disc of follow() only needs to hold `to` and meet no
  // shape (and it is convex, so it holds the moves between its points too): still exact.
  const bool line_binds = clearance > 0.0 && nearest_shape < lines_.size() && others > nearest;
  if (!line_binds) return;
  const double shift = std::min(0.5 * (others - nearest), kMaxDiscShift);
  const PreparedLine& line = lines_[nearest_shape];
  // (-dy, dx) / length: the unit normal toward positive signed distances.
  const double away =
      (line_state(index, nearest_shape).distance > 0.0 ? shift : -shift) * line.inverse_length;
  const Point centre{to.x - line.dy * away, to.y + line.dx * away};
  const double radius = std::min(nearest + shift, others - shift) - kDiscRounding;
  if (!(std::isfinite(centre.x) && std::isfinite(centre.y) && radius > nearest)) return;
  slot.look = centre;
  slot.clearance = radius;
}

void EventCounter::look(std::uint32_t index, const Point& from, const Point& to, double band,
                        bool first, double time) {
  Slot& slot = slots_[index];
  const std::size_t lines = lines_.size();
  const std::size_t shapes = lines + config_.zones.size();
  double clearance = INFINITY;
  std::uint64_t undecided = 0;
  double nearest = INFINITY;           // the nearest decided shape's clearance
  std::size_t nearest_shape = shapes;  // none
  double others = INFINITY;            // every other decided shape's
  const auto look_at = [&](std::size_t k) {
    const double c = k < lines ? look_at_line(index, k, from, to, band, first, time)
                               : look_at_zone(index, k - lines, from, to, band, first, time);
    clearance = std::min(clearance, c);
    if (c > 0.0) {
      if (c < nearest) {
        others = std::min(others, nearest);
        nearest = c;
        nearest_shape = k;
      } else {
        others = std::min(others, c);
      }
    } else if (k < ShapeGrid::kMaxShapes) {
      undecided |= std::uint64_t{1} << k;
    }
  };
  // A track near one shape (or within the band of some) is looked at often. While it stays
  // nearer to where the grid was last read than the other shapes' clearance from there (less
  // the band), they have nothing to decide (as in follow()): only the near ones are looked at.
  if (!first && slot.near != 0) {
    const double fx = to.x - slot.full_look.x;
    const double fy = to.y - slot.full_look.y;
    const double room = slot.others - band;
    if (room > 0.0 && fx * fx + fy * fy < room * room) {
      const double base = slot.others - std::sqrt(fx * fx + fy * fy);
      clearance = base;
      for (std::uint64_t near = slot.near; near != 0; near &= near - 1)
        look_at(static_cast<std::size_t>(__builtin_ctzll(near)));
      place_disc(slot, index, to, clearance, std::min(base, others), nearest, nearest_shape);
      slot.undecided = undecided;
      return;
    }
  }
  // The grid's cell of `to` names the shapes near it (its candidates); every other shape is at
  // least the cell's clearance away from `to`. When that is more than the band plus the move,
  // the whole move stayed beyond the band of each of them, and each was decided when last
  // looked at (the undecided are looked at anyway): they have nothing to decide. Otherwise (a
  // long move, a track off the grid, its first report) every shape is looked at.
  const std::uint32_t cell = first ? ShapeGrid::kOutside : grid_.cell_of(to);
  bool all = true;
  if (cell != ShapeGrid::kOutside) {
    const ShapeGrid::Cell& near_to = grid_.cell(cell);
    const double room = near_to.clearance - band;
    const double mx = to.x - from.x;
    const double my = to.y - from.y;
    if (room > 0.0 && mx * mx + my * my < room * room) {
      all = false;
      clearance = near_to.clearance;
      others = near_to.clearance;
      for (std::uint64_t near = near_to.candidates | slot.undecided; near != 0; near &= near - 1)
        look_at(static_cast<std::size_t>(__builtin_ctzll(near)));
    }
  }
  if (all)
    for (std::size_t k = 0; k < shapes; ++k) look_at(k);
  // (`others` holds the cell's clearance where the grid was read.)
  place_disc(slot, index, to, clearance, others, nearest, nearest_shape);
  slot.undecided = undecided;
  // The near ones: the undecided and the nearest decided (with more shapes than bits: none).
  slot.near = !grid_.enabled()          ? 0
              : nearest_shape == shapes ? undecided
                                        : undecided | std::uint64_t{1} << nearest_shape;
  slot.full_look = to;
  slot.others = others;
}

void EventCounter::count_crossing(std::size_t line, const Slot& slot, int side, const Point& where,
                                  double time) {
  const bool in = (side < 0) == config_.lines[line].in_is_left;
  emit(in ? EventKind::line_in : EventKind::line_out, line, slot, where, time);
  auto& counts = line_counts_[line];
  ++(in ? counts.in : counts.out);
}

double EventCounter::look_at_zone(std::uint32_t index, std::size_t z, const Point& from,
                                  const Point& to, double band, bool first, double time) {
  ZoneState& state = zone_state(index, z);
  const ZoneSpec& zone = config_.zones[z];
  const Bounds& bounds = zone_bounds_[z];
  // Most tracks are far from most zones: a move whose box, grown by the band, misses the zone's
  // box is outside by more than the band at both ends and cannot pass through.
  if (std::max(from.x, to.x) + band < bounds.min_x ||
      std::min(from.x, to.x) - band > bounds.max_x ||
      std::max(from.y, to.y) + band < bounds.min_y ||
      std::min(from.y, to.y) - band > bounds.max_y) {
    if (state.inside) leave(index, z, to, time, /*lost=*/false);
    // How far outside the zone's box: no further than from the zone itself.
    const double outside_x = std::max({bounds.min_x - to.x, to.x - bounds.max_x, 0.0});
    const double outside_y = std::max({bounds.min_y - to.y, to.y - bounds.max_y, 0.0});
    state.look = to;
    state.clearance = std::sqrt(outside_x * outside_x + outside_y * outside_y);
    return state.clearance;
  }
  // A move from and to points of the disc where the zone was last decided stays farther than the
  // band from the border, on the side it was decided: nothing to decide, and no border distance
  // to work out (a track inside a zone's box is near it for many updates).
  const double room = state.clearance - band;
  if (room > 0.0) {
    const double tx = to.x - state.look.x;
    const double ty = to.y - state.look.y;
    const double fx = from.x - state.look.x;
    const double fy = from.y - state.look.y;
    const double squared_room = room * room;
    if (tx * tx + ty * ty < squared_room && fx * fx + fy * fy < squared_room)
      return state.clearance - std::sqrt(tx * tx + ty * ty);
  }
  const double distance = distance_to_boundary_beyond(zone_edges_[z], to, band);
  if (distance <= band) {  // the dead band: decides nothing
    state.clearance = 0.0;
    return 0.0;
  }
  // A zone decided at its last look (a clearance) has had nothing come within its band since
  // (it would have been looked at): `from` is on the side it says, and a move shorter than the
  // distance of `to` from the border stays there. No even-odd test then.
  const bool inside = state.clearance > 0.0 && within(from, to, distance)
                          ? state.inside
                          : inside_polygon(zone.polygon, to);
  if (inside != state.inside) {
    if (inside) {
      enter(index, z, to, time);
    } else {
      leave(index, z, to, time, /*lost=*/false);
    }
  } else if (!inside && !first && !within(from, to, distance) &&
             move_meets_boundary(zone.polygon, from, to) &&
             distance_to_boundary_beyond(zone_edges_[z], from, band) > band) {
    // Through the zone between two processed frames: it was inside, for an unknown while.
    enter(index, z, to, time);
    leave(index, z, to, time, /*lost=*/false);
  }
  state.look = to;
  state.clearance = distance;
  return distance;
}

void EventCounter::enter(std::uint32_t index, std::size_t zone, const Point& where, double time) {
  ZoneState& state = zone_state(index, zone);
  state.inside = true;
  state.dwell_sent = false;
  state.clearance = 0.0;  // the disc was of the other side
  state.entered_at = time;
  earliest_pending_[zone] = std::min(earliest_pending_[zone], time);
  if (config_.zones[zone].dwell_seconds > 0.0)
    next_dwell_due_ = std::min(next_dwell_due_, due_from(time, config_.zones[zone].dwell_seconds));
  emit(EventKind::zone_enter, zone, slots_[index], where, time);
  ++zone_counts_[zone].entered;
  ++zone_counts_[zone].occupancy;
}

void EventCounter::leave(std::uint32_t index, std::size_t zone, const Point& where, double time,
                         bool lost) {
  ZoneState& state = zone_state(index, zone);
  emit(EventKind::zone_exit, zone, slots_[index], where, time, time - state.entered_at, lost);
  state.inside = false;
  state.clearance = 0.0;  // the disc was of the other side
  auto& counts = zone_counts_[zone];
  ++counts.exited;
  if (lost) ++counts.lost_inside;
  --counts.occupancy;
}

void EventCounter::dwell(double time) {
  if (time < next_dwell_due_) return;  // no zone has a visit due: one comparison per update
  next_dwell_due_ = INFINITY;
  for (std::size_t z = 0; z < config_.zones.size(); ++z) {
    const double threshold = config_.zones[z].dwell_seconds;
    // No visit can be due before the earliest one waiting (a bound: exits do not raise it).
    if (!(threshold > 0.0) || time - earliest_pending_[z] < threshold) continue;
    double earliest = INFINITY;
    for (const std::uint32_t index : live_) {
      ZoneState& state = zone_state(index, z);
      if (!state.inside || state.dwell_sent) continue;
      if (time - state.entered_at < threshold) {
        earliest = std::min(earliest, state.entered_at);
        continue;
      }
      state.dwell_sent = true;
      emit(EventKind::zone_dwell, z, slots_[index], slots_[index].anchor, time,
           time - state.entered_at);
      ++zone_counts_[z].dwelled;
    }
    earliest_pending_[z] = earliest;
  }
  for (std::size_t z = 0; z < config_.zones.size(); ++z)
    if (config_.zones[z].dwell_seconds > 0.0 && std::isfinite(earliest_pending_[z]))
      next_dwell_due_ =
          std::min(next_dwell_due_, due_from(earliest_pending_[z], config_.zones[z].dwell_seconds));
}

void EventCounter::forget(std::uint32_t index, double time) {
  // A track that ends inside the dead band of a line, on the other side from the one it had, after
  // meeting the line: it crossed, and no jitter can take it back now. Its last position decides.
  const Point& last = slots_[index].anchor;
  for (std::size_t l = 0; l < config_.lines.size(); ++l) {
    const LineState& state = line_state(index, l);
    const double distance = signed_distance(config_.lines[l].segment, last);
    const int side = (distance > 0.0) - (distance < 0.0);
    if (state.side != 0 && side != 0 && side != state.side && state.met_within_ends)
      count_crossing(l, slots_[index], side, last, time);
  }
  // A track that dies inside a zone leaves it now, marked lost: occupancy must not keep the dead.
  for (std::size_t z = 0; z < config_.zones.size(); ++z)
    if (zone_state(index, z).inside) leave(index, z, slots_[index].anchor, time, /*lost=*/true);
  slots_[index].live = false;
  const auto at = std::find(live_.begin(), live_.end(), index);
  *at = live_.back();
  live_.pop_back();
  free_.push_back(index);
}

void EventCounter::emit(EventKind kind, std::size_t index, const Slot& slot, const Point& where,
                        double time, double dwell_seconds, bool lost) {
  Event event;
  event.kind = kind;
  event.index = static_cast<std::uint16_t>(index);
  event.track_id = slot.track_id;
  event.class_id = slot.class_id;
  event.time = time;
  event.dwell_seconds = dwell_seconds;
  event.x = static_cast<float>(where.x);
  event.y = static_cast<float>(where.y);
  event.lost = lost;
  events_.push_back(event);
}

}  // namespace rtmot::events
