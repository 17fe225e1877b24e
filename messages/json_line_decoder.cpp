#include "messages/json_line_decoder.hpp"

#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "messages/jsonl_sink.hpp"

namespace rtmot::messages {
namespace {

using nlohmann::json;

// A listener is not a hot path (one message per frame per board): nlohmann's tree is the simple,
// well-kept reader; the writer formats by hand only because it runs on the board.
template <typename T>
T required(const json& object, const char* field) {
  const auto found = object.find(field);
  if (found == object.end()) throw std::invalid_argument(std::string("no \"") + field + '"');
  if constexpr (std::is_same_v<T, std::string>) {
    if (!found->is_string())
      throw std::invalid_argument(std::string("\"") + field + "\" is not a string");
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!found->is_boolean())
      throw std::invalid_argument(std::string("\"") + field + "\" is not true/false");
  } else if constexpr (std::is_floating_point_v<T>) {
    // JSON has no NaN: the writer sends null for a non-finite number.
    if (found->is_null()) return std::numeric_limits<T>::quiet_NaN();
    if (!found->is_number())
      throw std::invalid_argument(std::string("\"") + field + "\" is not a number");
  } else {
    if (!found->is_number_integer())
      throw std::invalid_argument(std::string("\"") + field + "\" is not an integer");
    if constexpr (std::is_unsigned_v<T>) {
      if (found->is_number_unsigned()) {
        if (found->get<std::uint64_t>() > std::numeric_limits<T>::max())
          throw std::invalid_argument(std::string("\"") + field + "\" is out of range");
      } else {
        throw std::invalid_argument(std::string("\"") + field + "\" is negative");
      }
    } else if (found->is_number_unsigned() &&
               found->get<std::uint64_t>() >
                   static_cast<std::uint64_t>(std::numeric_limits<T>::max())) {
      throw std::invalid_argument(std::string("\"") + field + "\" is out of range");
    } else if (!found->is_number_unsigned() &&
               (found->get<std::int64_t>() < std::numeric_limits<T>::min() ||
                found->get<std::int64_t>() > std::numeric_limits<T>::max())) {
      throw std::invalid_argument(std::string("\"") + field + "\" is out of range");
    }
  }
  return found->get<T>();
}

}  // namespace

bool looks_like_json(const std::uint8_t* data, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    const auto c = data[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') continue;
    return c == '{';
  }
  return false;
}

bool decode_json_line(const std::uint8_t* data, std::size_t size, DecodedMessage& out,
                      std::string& problem) {
  const json line = json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (line.is_discarded() || !line.is_object()) {
    problem = "not a JSON object";
    return false;
  }
  try {
    const int schema = required<int>(line, "schema");
    if (schema < 1 || schema > json_schema_version) {
      problem = "schema " + std::to_string(schema) + " is not one this reader knows (1.." +
                std::to_string(json_schema_version) + ")";
      return false;
    }
    FrameResult& frame = out.frame;
    frame.stream_id = required<std::uint32_t>(line, "stream");
    frame.sequence = required<std::uint64_t>(line, "sequence");
    frame.frame_number = required<std::int64_t>(line, "frame");
    frame.pts_ns = required<std::int64_t>(line, "pts_ns");
    frame.frames_dropped = required<std::uint32_t>(line, "frames_dropped");
    frame.source_outage = line.contains("source_outage") && required<bool>(line, "source_outage");
    frame.end_of_stream = line.contains("end_of_stream") && required<bool>(line, "end_of_stream");
    frame.predicted = line.contains("predicted") && required<bool>(line, "predicted");
    frame.observed =
        frame.predicted && line.contains("observed") && required<bool>(line, "observed");
    frame.times = FrameTimes{};
    frame.times.captured_ns = required<std::int64_t>(line, "captured_ns");
    frame.times.sent_ns = frame.times.captured_ns + required<std::int64_t>(line, "latency_ns");
    const bool truncated = required<bool>(line, "truncated");
    out.total_track_count = required<std::uint32_t>(line, "total_tracks");
    out.version = static_cast<std::uint8_t>(schema);
    out.flags = static_cast<std::uint8_t>((truncated ? message::flag_truncated : 0) |
                                          (frame.source_outage ? message::flag_source_outage : 0) |
                                          (frame.end_of_stream ? message::flag_end_of_stream : 0) |
                                          (frame.predicted ? message::flag_predicted : 0) |
                                          (frame.observed ? message::flag_observed : 0));
    const auto tracks = line.find("tracks");
    if (tracks == line.end() || !tracks->is_array()) {
      problem = "no \"tracks\" array";
      return false;
    }
    if (tracks->size() > out.total_track_count) {
      problem = "more \"tracks\" than \"total_tracks\"";
      return false;
    }
    frame.tracks.clear();
    for (const json& track : *tracks) {
      if (!track.is_object()) throw std::invalid_argument("a track is not an object");
      tracker::TrackReport report;
      report.id = required<std::int32_t>(track, "id");
      report.class_id = required<std::int32_t>(track, "class");
      report.score = required<float>(track, "score");
      report.box = tracker::Box{required<float>(track, "x"), required<float>(track, "y"),
                                required<float>(track, "w"), required<float>(track, "h")};
      report.hits = required<std::int32_t>(track, "hits");
      report.age = required<std::int32_t>(track, "age");
      frame.tracks.push_back(report);
    }
    frame.run_id = 0;
    if (const auto run = line.find("run"); run != line.end()) {
      const std::string text = run->is_string() ? run->get<std::string>() : "";
      std::size_t used = 0;
      try {
        frame.run_id = text.size() == 16 ? std::stoull(text, &used, 16) : 0;
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != 16) throw std::invalid_argument("\"run\" is not 16 hex digits");
    }
    const bool sized = line.contains("width") || line.contains("height");
    frame.frame_width = sized ? required<std::uint16_t>(line, "width") : 0;
    frame.frame_height = sized ? required<std::uint16_t>(line, "height") : 0;
    frame.events.clear();
    if (const auto events = line.find("events"); events != line.end()) {
      if (!events->is_array()) throw std::invalid_argument("\"events\" is not an array");
      for (const json& item : *events) {
        if (!item.is_object()) throw std::invalid_argument("an event is not an object");
        events::Event event;
        const auto kind = events::kEventKindNames.parse(required<std::string>(item, "kind"));
        if (!kind) throw std::invalid_argument("an event's \"kind\" is not one this reader knows");
        event.kind = *kind;
        event.index = required<std::uint16_t>(item, "index");
        event.track_id = required<std::int32_t>(item, "track");
        event.class_id = required<std::int32_t>(item, "class");
        event.x = required<float>(item, "x");
        event.y = required<float>(item, "y");
        event.dwell_seconds = required<double>(item, "dwell_s");
        event.lost = required<bool>(item, "lost");
        event.time = static_cast<double>(frame.pts_ns) * 1e-9;
        frame.events.push_back(event);
      }
    }
  } catch (const std::exception& error) {  // ours (a field) or nlohmann's (a type)
    problem = error.what();
    return false;
  }
  return true;
}

}  // namespace rtmot::messages
