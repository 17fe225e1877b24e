#include "outputs/event_metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "common/utf8.hpp"

namespace rtmot::outputs {
namespace {

constexpr auto relaxed = std::memory_order_relaxed;
constexpr std::size_t kZoneFields = 4;  // enter, exit, lost inside, dwell

// A label value as the text format wants it: UTF-8 (names are checked where they are read,
// events/events_yaml.cpp; a name made another way gets U+FFFD for a byte that is not), backslash,
// double quote and newline escaped.
std::string label_value(const std::string& name) {
  const std::string text = replace_invalid_utf8(name);
  std::string out;
  for (const char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    out += c == '\n' ? 'n' : c;
    if (c == '\n') out.insert(out.size() - 1, 1, '\\');
  }
  return out;
}

std::unique_ptr<std::atomic<std::uint64_t>[]> zeroed(std::size_t n) {
  auto values = std::make_unique<std::atomic<std::uint64_t>[]>(n);
  for (std::size_t i = 0; i < n; ++i) values[i].store(0, relaxed);
  return values;
}

}  // namespace

std::unique_ptr<EventMetrics::Counters> EventMetrics::make_counters(
    Source source, std::uint32_t generation) const {
  auto counters = std::make_unique<Counters>();
  counters->lines = zeroed(2 * source.lines.size());
  counters->zones = zeroed(kZoneFields * source.zones.size());
  counters->by_class = zeroed(2 * (source.lines.size() + source.zones.size()) * class_columns_);
  counters->source = std::move(source);
  counters->generation = generation;
  return counters;
}

EventMetrics::EventMetrics(std::vector<Source> sources, int class_columns,
                           messages::ClassLabelFn labels)
    : class_columns_(static_cast<std::size_t>(std::max(class_columns, 0))),
      labels_(std::move(labels)) {
  for (auto& source : sources) {
    auto stream = std::make_unique<Stream>();
    stream->stream_id = source.stream_id;
    kept_.push_back(make_counters(std::move(source), 0));
    stream->current.store(kept_.back().get(), relaxed);  // before any other thread exists
    streams_.push_back(std::move(stream));
  }
}

bool EventMetrics::post(Source source, std::uint32_t generation) {
  const auto found = std::find_if(streams_.begin(), streams_.end(),
                                  [&](const auto& s) { return s->stream_id == source.stream_id; });
  if (found == streams_.end()) return false;
  const std::lock_guard<std::mutex> lock(posters_);
  kept_.push_back(make_counters(std::move(source), generation));
  // release: the zeroed counters and the names are whole before the sink thread acquires them.
  (*found)->pending.store(kept_.back().get(), std::memory_order_release);
  return true;
}

std::vector<const EventMetrics::Counters*> EventMetrics::current() const {
  std::vector<const Counters*> sets;
  for (const auto& stream : streams_) {
    sets.push_back(stream->current.load(std::memory_order_acquire));
  }
  return sets;
}

void EventMetrics::count_class(Counters& counters, std::size_t slot, std::int32_t class_id) const {
  // A class the labels do not have is in the totals only.
  if (class_id < 0 || static_cast<std::size_t>(class_id) >= class_columns_) return;
  counters.by_class[slot * class_columns_ + static_cast<std::size_t>(class_id)].fetch_add(1,
                                                                                          relaxed);
}

void EventMetrics::observe(const messages::FrameResult& result) {
  const auto stream = std::find_if(streams_.begin(), streams_.end(),
                                   [&](const auto& s) { return s->stream_id == result.stream_id; });
  if (stream == streams_.end()) return;
  Counters* found = (*stream)->current.load(relaxed);  // this thread is its only writer
  if (found->generation != result.events_generation) {
    Counters* next = (*stream)->pending.load(std::memory_order_acquire);
    if (next == nullptr || next->generation != result.events_generation) return;
    (*stream)->current.store(next, std::memory_order_release);  // for the readers
    found = next;
  }
  for (const auto& event : result.events) {
    const std::size_t index = event.index;
    switch (event.kind) {
      case events::EventKind::line_in:
      case events::EventKind::line_out:
        if (index < found->source.lines.size()) {
          const std::size_t slot = 2 * index + (event.kind == events::EventKind::line_in ? 0 : 1);
          found->lines[slot].fetch_add(1, relaxed);
          count_class(*found, slot, event.class_id);
        }
        break;
      case events::EventKind::zone_enter:
      case events::EventKind::zone_exit:
      case events::EventKind::zone_dwell:
        if (index < found->source.zones.size()) {
          std::atomic<std::uint64_t>* zone = &found->zones[kZoneFields * index];
          if (event.kind == events::EventKind::zone_enter) zone[0].fetch_add(1, relaxed);
          if (event.kind == events::EventKind::zone_exit) zone[1].fetch_add(1, relaxed);
          if (event.kind == events::EventKind::zone_exit && event.lost)
            zone[2].fetch_add(1, relaxed);
          if (event.kind == events::EventKind::zone_dwell) zone[3].fetch_add(1, relaxed);
          if (event.kind != events::EventKind::zone_dwell) {
            count_class(*found,
                        2 * (found->source.lines.size() + index) +
                            (event.kind == events::EventKind::zone_enter ? 0 : 1),
                        event.class_id);
          }
        }
        break;
    }
  }
}

void EventMetrics::render(std::string& out) const {
  if (streams_.empty()) return;
  const std::vector<const Counters*> sets = current();
  auto to = std::back_inserter(out);
  fmt::format_to(to,
                 "# HELP rtmot_line_crossings_total Tracks that crossed a counting line, by "
                 "direction (docs/events.md).\n# TYPE rtmot_line_crossings_total counter\n");
  for (const Counters* set : sets) {
    const Counters& c = *set;
    for (std::size_t l = 0; l < c.source.lines.size(); ++l) {
      for (const int direction : {0, 1}) {
        fmt::format_to(
            to, "rtmot_line_crossings_total{{stream=\"{}\",line=\"{}\",direction=\"{}\"}} {}\n",
            c.source.stream_id, label_value(c.source.lines[l]), direction == 0 ? "in" : "out",
            c.lines[2 * l + direction].load(relaxed));
      }
    }
  }
  fmt::format_to(
      to,
      "# HELP rtmot_zone_events_total Zone enters, exits (lost: of tracks that died "
      "inside, counted in exit too) and dwells.\n# TYPE rtmot_zone_events_total counter\n");
  static constexpr const char* kNames[kZoneFields] = {"enter", "exit", "lost", "dwell"};
  for (const Counters* set : sets) {
    const Counters& c = *set;
    for (std::size_t z = 0; z < c.source.zones.size(); ++z) {
      for (std::size_t f = 0; f < kZoneFields; ++f) {
        fmt::format_to(to, "rtmot_zone_events_total{{stream=\"{}\",zone=\"{}\",event=\"{}\"}} {}\n",
                       c.source.stream_id, label_value(c.source.zones[z]), kNames[f],
                       c.zones[kZoneFields * z + f].load(relaxed));
      }
    }
  }
  fmt::format_to(to,
                 "# HELP rtmot_zone_occupancy Tracks inside a zone now (enters minus exits).\n"
                 "# TYPE rtmot_zone_occupancy gauge\n");
  for (const Counters* set : sets) {
    const Counters& c = *set;
    for (std::size_t z = 0; z < c.source.zones.size(); ++z) {
      const auto entered = c.zones[kZoneFields * z].load(relaxed);
      const auto exited = c.zones[kZoneFields * z + 1].load(relaxed);
      fmt::format_to(to, "rtmot_zone_occupancy{{stream=\"{}\",zone=\"{}\"}} {}\n",
                     c.source.stream_id, label_value(c.source.zones[z]),
                     entered >= exited ? entered - exited : 0);
    }
  }
}

// The classes with any count in `slot` and its pair (in/out, enter/exit), by name.
nlohmann::json EventMetrics::classes_of(const Counters& counters, std::size_t slot) const {
  const bool line = slot < 2 * counters.source.lines.size();
  nlohmann::json classes = nlohmann::json::object();
  for (std::size_t c = 0; c < class_columns_; ++c) {
    const auto first = counters.by_class[slot * class_columns_ + c].load(relaxed);
    const auto second = counters.by_class[(slot + 1) * class_columns_ + c].load(relaxed);
    if (first == 0 && second == 0) continue;
    const auto id = static_cast<int>(c);
    std::string name = labels_ ? std::string(labels_(id)) : std::string();
    if (name.empty()) name = std::to_string(id);
    classes[replace_invalid_utf8(name)] = {{line ? "in" : "enter", first},
                                           {line ? "out" : "exit", second}};
  }
  return classes;
}

nlohmann::json EventMetrics::status() const {
  nlohmann::json sources = nlohmann::json::array();
  const std::vector<const Counters*> sets = current();
  for (const Counters* set : sets) {
    const Counters& c = *set;
    nlohmann::json lines = nlohmann::json::array();
    for (std::size_t l = 0; l < c.source.lines.size(); ++l) {
      lines.push_back({{"name", replace_invalid_utf8(c.source.lines[l])},
                       {"in", c.lines[2 * l].load(relaxed)},
                       {"out", c.lines[2 * l + 1].load(relaxed)},
                       {"classes", classes_of(c, 2 * l)}});
    }
    nlohmann::json zones = nlohmann::json::array();
    for (std::size_t z = 0; z < c.source.zones.size(); ++z) {
      const std::atomic<std::uint64_t>* zone = &c.zones[kZoneFields * z];
      const auto entered = zone[0].load(relaxed);
      const auto exited = zone[1].load(relaxed);
      zones.push_back({{"name", replace_invalid_utf8(c.source.zones[z])},
                       {"enter", entered},
                       {"exit", exited},
                       {"lost", zone[2].load(relaxed)},
                       {"dwell", zone[3].load(relaxed)},
                       {"occupancy", entered >= exited ? entered - exited : 0},
                       {"classes", classes_of(c, 2 * (c.source.lines.size() + z))}});
    }
    // generation > 0: the page saved these lines and zones, and their counts began then.
    sources.push_back({{"stream", c.source.stream_id},
                       {"generation", c.generation},
                       {"lines", lines},
                       {"zones", zones}});
  }
  return sources;
}

}  // namespace rtmot::outputs
