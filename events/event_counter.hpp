#pragma once
// Counts line crossings and zone visits from a tracker's reports, update by update. Decides on the
// path of each track between its reported positions, so a crossing between two processed frames
// far apart (a detector slower than the camera) counts once, and with a dead band that grows with
// the stream's own box jitter, so a box wobbling on a line does not count again and again.
// Allocation-free after construction: the track table, the per-line and per-zone state and the
// event list are sized once for config.max_tracks tracks.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "events/event.hpp"
#include "events/events_config.hpp"
#include "events/shape_grid.hpp"
#include "tracker/box.hpp"
#include "tracker/recent_window.hpp"

namespace rtmot::events {

class EventCounter {
 public:
  /// `config` must be valid (events/events_yaml.hpp checks a user's).
  explicit EventCounter(EventsConfig config);

  /// One processed frame's reports, at `time_seconds` (the pipeline's timestamp, increasing).
  /// Returns the events it decided; the reference stays valid until the next call.
  const std::vector<Event>& update(const std::vector<tracker::TrackReport>& reports,
                                   double time_seconds);

  /// The end of the stream: every track still followed is lost now (zone exits with lost set).
  const std::vector<Event>& finish(double time_seconds);

  const EventsConfig& config() const { return config_; }
  const std::vector<LineCounts>& line_counts() const { return line_counts_; }
  const std::vector<ZoneCounts>& zone_counts() const { return zone_counts_; }
  /// The box jitter the dead band scales with: the median second difference of a track's box
  /// size over three consecutive updates, (|ddw| / w + |ddh| / h) / 2 (the tracker's BoxNoise
  /// units: a share of the box size).
  double box_noise() const { return box_noise_; }
  /// Reports skipped because max_tracks tracks were already followed.
  std::int64_t tracks_not_followed() const { return tracks_not_followed_; }

 private:
  struct PreparedLine {
    Point from;
    double dx;
    double dy;
    double inverse_length;
    double inverse_squared_length;
  };
  struct Bounds {
    double min_x;
    double min_y;
    double max_x;
    double max_y;
  };
  struct LineState {
    double distance{0.0};         // signed distance of the last position
    std::int8_t side{0};          // -1 left, +1 right, 0 not yet known
    bool met_within_ends{false};  // the path since the last decided side met the segment
    std::int64_t looked_at{-1};   // the update that computed `distance`
  };
  struct ZoneState {
    bool inside{false};
    bool dwell_sent{false};
    double entered_at{0.0};
    // Where the zone was last decided, and how far its border was from there (0: no disc). Every
    // point of that disc is on the side `inside` says, so a move within it decides nothing.
    Point look;
    double clearance{0.0};
  };
  // A box's size as the tracker reports it (floats: half the bytes of doubles, the same values).
  struct Size {
    float w{0.F};
    float h{0.F};
  };
  // What follow() reads for every report first (the skip test), then what it writes.
  struct Slot {
    bool live{false};
    std::int32_t track_id{0};
    std::int32_t class_id{0};
    // The disc of follow(): no shape meets it, the last position looked at is in it (its centre,
    // or moved away from a line or a zone's box: place_disc()).
    Point look;
    double clearance{0.0};
    double last_seen{0.0};
    std::int64_t last_update{-1};
    Point anchor;
    Size size;
    Size previous_size;
    double previous_seen{0.0};
    std::int64_t previous_update{-1};
    // The shapes (bit k: shape k, lines first) that were within the band when last looked at:
    // their side or visit is undecided, and they are looked at again whatever the grid says.
    std::uint64_t undecided{0};
    // Where the grid was last read, the shapes near the track then (the undecided and the
    // nearest decided one) and the smallest clearance of all others from there: while the track
    // stays nearer to there than that less the band, only the near ones are looked at.
    Point full_look;
    std::uint64_t near{0};
    double others{0.0};
  };

  static constexpr std::uint32_t kNone = ~std::uint32_t{0};

  bool counts_class(std::int32_t class_id) const {
    return config_.classes.empty() || std::find(config_.classes.begin(), config_.classes.end(),
                                                class_id) != config_.classes.end();
  }
  // One update's settings, as update() hands them to follow() for each report.
  struct PerUpdate {
    bool measuring_noise;  // the box noise, in this update
    bool bottom_centre;    // the anchor
    double min_band;
    double noise_factor;
    std::int64_t update;
  };
  static Point anchor_at(const tracker::Box& box, bool bottom_centre) {
    const double x = double{box.x} + 0.5 * box.w;
    const double y = bottom_centre ? double{box.y} + box.h : double{box.y} + 0.5 * box.h;
    return {x, y};
  }
  std::uint32_t find_live(std::int32_t track_id) const;
  std::uint32_t find_broken_off(const tracker::TrackReport& report, double time) const;
  Point anchor_of(const tracker::Box& box) const;
  void measure_noise(const Slot& slot, const tracker::Box& box, double time);
  void settle_noise();
  void count_crossing(std::size_t line, const Slot& slot, int side, const Point& where,
                      double time);
  void follow(std::uint32_t index, const tracker::TrackReport& report, double time,
              const PerUpdate& now);
  // Looks at the shapes that the move from `from` to `to` may have brought within their band.
  void look(std::uint32_t index, const Point& from, const Point& to, double band, bool first,
            double time);
  // Sets the disc of follow() after a look from `to`: `clearance` of every shape looked at and
  // the bound of the others, `others` the same without the nearest decided shape, `nearest` its.
  void place_disc(Slot& slot, std::uint32_t index, const Point& to, double clearance, double others,
                  double nearest, std::size_t nearest_shape);
  // Each looks at one shape for a track moving from `from` to `to`, decides what it can, and
  // returns the shape's clearance from `to` (follow(): 0 within the band).
  double look_at_line(std::uint32_t index, std::size_t line, const Point& from, const Point& to,
                      double band, bool first, double time);
  double look_at_zone(std::uint32_t index, std::size_t zone, const Point& from, const Point& to,
                      double band, bool first, double time);
  void enter(std::uint32_t index, std::size_t zone, const Point& where, double time);
  void leave(std::uint32_t index, std::size_t zone, const Point& where, double time, bool lost);
  void dwell(double time);
  void forget(std::uint32_t index, double time);
  void emit(EventKind kind, std::size_t index, const Slot& slot, const Point& where, double time,
            double dwell_seconds = 0.0, bool lost = false);
  LineState& line_state(std::size_t slot, std::size_t line) {
    return line_states_[slot * config_.lines.size() + line];
  }
  ZoneState& zone_state(std::size_t slot, std::size_t zone) {
    return zone_states_[slot * config_.zones.size() + zone];
  }

  EventsConfig config_;
  std::vector<PreparedLine> lines_;
  std::vector<Bounds> zone_bounds_;
  std::vector<std::vector<PreparedEdge>> zone_edges_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> live_;  // slots in use, in no order
  std::vector<std::uint32_t> free_;
  std::vector<std::uint32_t> hints_;   // the slot of the report at each position last update
  std::vector<std::uint32_t> births_;  // this update's reports of ids not followed yet
  std::vector<LineState> line_states_;
  std::vector<ZoneState> zone_states_;
  ShapeGrid grid_;
  std::vector<Event> events_;
  std::vector<LineCounts> line_counts_;
  std::vector<ZoneCounts> zone_counts_;
  // Per zone: no visit without its dwell event entered before this (INFINITY: none waits).
  std::vector<double> earliest_pending_;
  // No zone has a visit due before this (dwell() is one comparison until then).
  double next_dwell_due_{INFINITY};
  tracker::RecentWindow noise_window_;
  double box_noise_{0.0};
  std::int64_t noise_values_{0};  // pushed into noise_window_
  std::int64_t updates_{0};
  std::int64_t tracks_not_followed_{0};
  // No live slot was last seen before this (a bound: the lost-track scan runs only when it can
  // find one).
  double oldest_seen_{INFINITY};
};

}  // namespace rtmot::events
