#include "messages/message_format.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace rtmot::messages {
namespace {

// Byte offsets of version 1 (docs/message-format.md).
namespace offset {
constexpr std::size_t magic = 0;
constexpr std::size_t version = 4;
constexpr std::size_t flags = 5;
constexpr std::size_t header_length = 6;
constexpr std::size_t stream_id = 8;
constexpr std::size_t frames_dropped = 12;
constexpr std::size_t sequence = 16;
constexpr std::size_t frame_number = 24;
constexpr std::size_t pts_ns = 32;
constexpr std::size_t captured_ns = 40;
constexpr std::size_t latency_ns = 48;
constexpr std::size_t track_count = 56;
constexpr std::size_t total_track_count = 58;
constexpr std::size_t track_record_length = 60;
constexpr std::size_t reserved = 62;
}  // namespace offset

// The header extension (docs/message-format.md, "Header extension").
namespace extension_offset {
constexpr std::size_t run_id = 64;
constexpr std::size_t event_count = 72;
constexpr std::size_t event_record_length = 74;
constexpr std::size_t total_event_count = 76;
constexpr std::size_t reserved = 78;
}  // namespace extension_offset

namespace event_offset {
constexpr std::size_t kind = 0;
constexpr std::size_t flags = 1;
constexpr std::size_t index = 2;
constexpr std::size_t track_id = 4;
constexpr std::size_t class_id = 8;
constexpr std::size_t x = 12;
constexpr std::size_t y = 16;
constexpr std::size_t dwell_ms = 20;
constexpr std::uint8_t flag_lost = 0x01;
}  // namespace event_offset

namespace track_offset {
constexpr std::size_t id = 0;
constexpr std::size_t x = 4;
constexpr std::size_t y = 8;
constexpr std::size_t w = 12;
constexpr std::size_t h = 16;
constexpr std::size_t score = 20;
constexpr std::size_t class_id = 24;
constexpr std::size_t hits = 26;
constexpr std::size_t age = 28;
}  // namespace track_offset

// Byte by byte rather than memcpy of host integers: the format is little-endian on every host.
template <typename Unsigned>
void put(std::uint8_t* at, Unsigned value) {
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) {
    at[i] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

template <typename Unsigned>
Unsigned get(const std::uint8_t* at) {
  Unsigned value = 0;
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) {
    value = static_cast<Unsigned>(value |
                                  static_cast<Unsigned>(static_cast<Unsigned>(at[i]) << (8 * i)));
  }
  return value;
}

void put_i64(std::uint8_t* at, std::int64_t value) {
  put<std::uint64_t>(at, static_cast<std::uint64_t>(value));
}
std::int64_t get_i64(const std::uint8_t* at) {
  return static_cast<std::int64_t>(get<std::uint64_t>(at));
}

void put_f32(std::uint8_t* at, float value) {
  static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "IEEE-754 float");
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  put<std::uint32_t>(at, bits);
}

float get_f32(const std::uint8_t* at) {
  const auto bits = get<std::uint32_t>(at);
  float value = 0.F;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

template <typename Narrow, typename Wide>
Narrow saturate(Wide value) {
  if (value < static_cast<Wide>(std::numeric_limits<Narrow>::min()))
    return std::numeric_limits<Narrow>::min();
  if (value > static_cast<Wide>(std::numeric_limits<Narrow>::max()))
    return std::numeric_limits<Narrow>::max();
  return static_cast<Narrow>(value);
}

std::uint32_t crc32_of(const std::uint8_t* data, std::size_t size) {
  // Messages are at most 64 KiB, so one call of zlib's uInt-sized crc32 covers them.
  return static_cast<std::uint32_t>(::crc32(0L, data, static_cast<uInt>(size)));
}

void write_track(std::uint8_t* at, const tracker::TrackReport& track) {
  put<std::uint32_t>(at + track_offset::id, static_cast<std::uint32_t>(track.id));
  put_f32(at + track_offset::x, track.box.x);
  put_f32(at + track_offset::y, track.box.y);
  put_f32(at + track_offset::w, track.box.w);
  put_f32(at + track_offset::h, track.box.h);
  put_f32(at + track_offset::score, track.score);
  put<std::uint16_t>(at + track_offset::class_id,
                     static_cast<std::uint16_t>(saturate<std::int16_t>(track.class_id)));
  put<std::uint16_t>(at + track_offset::hits, saturate<std::uint16_t>(track.hits));
  put<std::uint32_t>(at + track_offset::age,
                     saturate<std::uint32_t>(static_cast<std::int64_t>(track.age)));
}

tracker::TrackReport read_track(const std::uint8_t* at) {
  tracker::TrackReport track;
  track.id = static_cast<std::int32_t>(get<std::uint32_t>(at + track_offset::id));
  track.box.x = get_f32(at + track_offset::x);
  track.box.y = get_f32(at + track_offset::y);
  track.box.w = get_f32(at + track_offset::w);
  track.box.h = get_f32(at + track_offset::h);
  track.score = get_f32(at + track_offset::score);
  track.class_id = static_cast<std::int16_t>(get<std::uint16_t>(at + track_offset::class_id));
  track.hits = get<std::uint16_t>(at + track_offset::hits);
  track.age = static_cast<std::int32_t>(std::min<std::uint32_t>(
      get<std::uint32_t>(at + track_offset::age),
      static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max())));
  return track;
}

void write_event(std::uint8_t* at, const events::Event& event) {
  at[event_offset::kind] = static_cast<std::uint8_t>(event.kind);
  at[event_offset::flags] = event.lost ? event_offset::flag_lost : 0;
  put<std::uint16_t>(at + event_offset::index, event.index);
  put<std::uint32_t>(at + event_offset::track_id, static_cast<std::uint32_t>(event.track_id));
  put<std::uint32_t>(at + event_offset::class_id, static_cast<std::uint32_t>(event.class_id));
  put_f32(at + event_offset::x, event.x);
  put_f32(at + event_offset::y, event.y);
  const double dwell_ms = std::round(event.dwell_seconds * 1000.0);
  put<std::uint32_t>(
      at + event_offset::dwell_ms,
      std::isfinite(dwell_ms) ? saturate<std::uint32_t>(std::max(dwell_ms, 0.0)) : 0U);
}

events::Event read_event(const std::uint8_t* at, std::int64_t pts_ns) {
  events::Event event;
  event.kind = static_cast<events::EventKind>(at[event_offset::kind]);
  event.lost = (at[event_offset::flags] & event_offset::flag_lost) != 0;
  event.index = get<std::uint16_t>(at + event_offset::index);
  event.track_id = static_cast<std::int32_t>(get<std::uint32_t>(at + event_offset::track_id));
  event.class_id = static_cast<std::int32_t>(get<std::uint32_t>(at + event_offset::class_id));
  event.x = get_f32(at + event_offset::x);
  event.y = get_f32(at + event_offset::y);
  event.dwell_seconds = get<std::uint32_t>(at + event_offset::dwell_ms) / 1000.0;
  event.time = static_cast<double>(pts_ns) * 1e-9;  // decided at this frame
  return event;
}

// NaN sorts last, so that the ordering stays strict-weak whatever the detector produced.
float score_key(float score) {
  return std::isnan(score) ? -std::numeric_limits<float>::infinity() : score;
}

}  // namespace

std::size_t MessageEncoder::encode(const FrameResult& result, std::uint8_t* buffer,
                                   std::size_t capacity) {
  if (capacity < message::min_size) return 0;
  const auto& tracks = result.tracks;
  // The extension only when there is something to put in it: a message without run id and
  // events is byte for byte what it was before the extension.
  const bool has_frame_size = result.frame_width != 0 && result.frame_height != 0;
  const bool extended = result.run_id != 0 || !result.events.empty() || has_frame_size;
  // The frame size goes after the events, so it costs its 4 bytes only when known.
  const std::size_t fixed_extension =
      message::header_extended_size + (has_frame_size ? message::frame_size_size : 0);
  const bool extension_fits = extended && capacity >= fixed_extension + message::crc_size;
  std::size_t events_sent = 0;
  if (extension_fits) {
    const std::size_t room =
        (capacity - fixed_extension - message::crc_size) / message::event_record_size;
    events_sent = std::min({result.events.size(), room, std::size_t{0xFFFF}});
  }
  const bool events_truncated = events_sent < result.events.size();
  const std::size_t header_length = extension_fits
                                        ? fixed_extension + events_sent * message::event_record_size
                                        : message::header_size;
  const std::size_t fit =
      std::min(message::max_track_count,
               (capacity - header_length - message::crc_size) / message::track_record_size);
  const bool truncated = tracks.size() > fit;
  const std::size_t sent = truncated ? fit : tracks.size();

  std::uint8_t* const header = buffer;
  put<std::uint32_t>(header + offset::magic, message::magic);
  header[offset::version] = message::version;
  header[offset::flags] =
      static_cast<std::uint8_t>((truncated ? message::flag_truncated : 0) |
                                (result.source_outage ? message::flag_source_outage : 0) |
                                (events_truncated ? message::flag_events_truncated : 0) |
                                (result.end_of_stream ? message::flag_end_of_stream : 0) |
                                (result.predicted ? message::flag_predicted : 0) |
                                (result.predicted && result.observed ? message::flag_observed : 0));
  put<std::uint16_t>(header + offset::header_length, static_cast<std::uint16_t>(header_length));
  put<std::uint32_t>(header + offset::stream_id, result.stream_id);
  put<std::uint32_t>(header + offset::frames_dropped, result.frames_dropped);
  put<std::uint64_t>(header + offset::sequence, result.sequence);
  put_i64(header + offset::frame_number, result.frame_number);
  put_i64(header + offset::pts_ns, result.pts_ns);
  put_i64(header + offset::captured_ns, result.times.captured_ns);
  // Unsigned subtraction: unset or wild times must not be signed-overflow UB.
  put<std::uint64_t>(header + offset::latency_ns,
                     static_cast<std::uint64_t>(result.times.sent_ns) -
                         static_cast<std::uint64_t>(result.times.captured_ns));
  put<std::uint16_t>(header + offset::track_count, static_cast<std::uint16_t>(sent));
  put<std::uint16_t>(header + offset::total_track_count, saturate<std::uint16_t>(tracks.size()));
  put<std::uint16_t>(header + offset::track_record_length,
                     static_cast<std::uint16_t>(message::track_record_size));
  put<std::uint16_t>(header + offset::reserved, 0);

  if (header_length >= message::header_extended_size) {
    put<std::uint64_t>(header + extension_offset::run_id, result.run_id);
    put<std::uint16_t>(header + extension_offset::event_count,
                       static_cast<std::uint16_t>(events_sent));
    put<std::uint16_t>(header + extension_offset::event_record_length,
                       static_cast<std::uint16_t>(message::event_record_size));
    put<std::uint16_t>(header + extension_offset::total_event_count,
                       saturate<std::uint16_t>(result.events.size()));
    put<std::uint16_t>(header + extension_offset::reserved, 0);
    for (std::size_t i = 0; i < events_sent; ++i) {
      write_event(header + message::header_extended_size + i * message::event_record_size,
                  result.events[i]);
    }
    if (has_frame_size) {
      std::uint8_t* const size_at =
          header + message::header_extended_size + events_sent * message::event_record_size;
      put<std::uint16_t>(size_at, result.frame_width);
      put<std::uint16_t>(size_at + 2, result.frame_height);
    }
  }
  std::uint8_t* record = buffer + header_length;
  if (!truncated) {
    for (const auto& track : tracks) {
      write_track(record, track);
      record += message::track_record_size;
    }
  } else {
    // Partial selection of the best `sent` scores, then back to the tracker's order so that a
    // truncated message reads like an untruncated one. Ties go to the lower index: deterministic.
    order_.resize(tracks.size());
    std::iota(order_.begin(), order_.end(), 0U);
    const auto better = [&tracks](std::uint32_t a, std::uint32_t b) {
      const float score_a = score_key(tracks[a].score);
      const float score_b = score_key(tracks[b].score);
      return score_a != score_b ? score_a > score_b : a < b;
    };
    const auto kept_end = order_.begin() + static_cast<std::ptrdiff_t>(sent);
    std::nth_element(order_.begin(), kept_end, order_.end(), better);
    std::sort(order_.begin(), kept_end);
    for (auto index = order_.begin(); index != kept_end; ++index) {
      write_track(record, tracks[*index]);
      record += message::track_record_size;
    }
  }
  const auto body_size = static_cast<std::size_t>(record - buffer);
  put<std::uint32_t>(record, crc32_of(buffer, body_size));
  return body_size + message::crc_size;
}

std::string_view to_string(DecodeError error) {
  switch (error) {
    case DecodeError::none:
      return "ok";
    case DecodeError::too_short:
      return "too short";
    case DecodeError::bad_magic:
      return "bad magic";
    case DecodeError::unsupported_version:
      return "unsupported version";
    case DecodeError::bad_header_length:
      return "bad header length";
    case DecodeError::bad_track_record_length:
      return "bad track record length";
    case DecodeError::bad_track_counts:
      return "track count above total";
    case DecodeError::length_mismatch:
      return "length mismatch";
    case DecodeError::bad_crc:
      return "bad CRC";
    case DecodeError::bad_event_counts:
      return "bad event counts";
  }
  return "unknown error";
}

DecodeError decode_message(const std::uint8_t* data, std::size_t size, DecodedMessage& out) {
  if (data == nullptr || size < message::min_size) return DecodeError::too_short;
  if (get<std::uint32_t>(data + offset::magic) != message::magic) return DecodeError::bad_magic;
  const std::uint8_t version = data[offset::version];
  if (version != message::version) return DecodeError::unsupported_version;

  // Every length is checked against `size` before anything past the fixed header is read. The
  // products are of 16-bit values in 64-bit arithmetic: they cannot overflow.
  const std::uint64_t header_length = get<std::uint16_t>(data + offset::header_length);
  if (header_length < message::header_size || header_length + message::crc_size > size) {
    return DecodeError::bad_header_length;
  }
  const std::uint64_t record_length = get<std::uint16_t>(data + offset::track_record_length);
  if (record_length < message::track_record_size) return DecodeError::bad_track_record_length;
  const std::uint64_t track_count = get<std::uint16_t>(data + offset::track_count);
  const std::uint64_t total_track_count = get<std::uint16_t>(data + offset::total_track_count);
  if (track_count > total_track_count) return DecodeError::bad_track_counts;
  if (header_length + record_length * track_count + message::crc_size != size) {
    return DecodeError::length_mismatch;
  }
  const std::size_t body_size = size - message::crc_size;
  if (get<std::uint32_t>(data + body_size) != crc32_of(data, body_size))
    return DecodeError::bad_crc;
  // The extension, when the header is long enough to hold it (a header between 64 and 80 bytes
  // is some other compatible addition: skipped, as an old reader skips this one).
  const bool extended = header_length >= message::header_extended_size;
  std::uint64_t event_count = 0;
  std::uint64_t event_length = message::event_record_size;
  if (extended) {
    event_count = get<std::uint16_t>(data + extension_offset::event_count);
    event_length = get<std::uint16_t>(data + extension_offset::event_record_length);
    if (event_length < message::event_record_size ||
        message::header_extended_size + event_count * event_length > header_length ||
        event_count > get<std::uint16_t>(data + extension_offset::total_event_count)) {
      return DecodeError::bad_event_counts;
    }
  }

  out.version = version;
  out.flags = data[offset::flags];
  out.total_track_count = static_cast<std::uint32_t>(total_track_count);
  FrameResult& frame = out.frame;
  frame.stream_id = get<std::uint32_t>(data + offset::stream_id);
  frame.frames_dropped = get<std::uint32_t>(data + offset::frames_dropped);
  frame.sequence = get<std::uint64_t>(data + offset::sequence);
  frame.frame_number = get_i64(data + offset::frame_number);
  frame.pts_ns = get_i64(data + offset::pts_ns);
  frame.source_outage = (out.flags & message::flag_source_outage) != 0;
  frame.end_of_stream = (out.flags & message::flag_end_of_stream) != 0;
  frame.predicted = (out.flags & message::flag_predicted) != 0;
  frame.observed = frame.predicted && (out.flags & message::flag_observed) != 0;
  frame.times = FrameTimes{};
  frame.times.captured_ns = get_i64(data + offset::captured_ns);
  // Unsigned addition: a hostile latency must not be signed-overflow UB.
  frame.times.sent_ns =
      static_cast<std::int64_t>(static_cast<std::uint64_t>(frame.times.captured_ns) +
                                get<std::uint64_t>(data + offset::latency_ns));
  frame.run_id = extended ? get<std::uint64_t>(data + extension_offset::run_id) : 0;
  // The frame size, when the header goes on past the events far enough to hold it.
  const std::uint64_t after_events = message::header_extended_size + event_count * event_length;
  const bool has_frame_size = extended && after_events + message::frame_size_size <= header_length;
  frame.frame_width = has_frame_size ? get<std::uint16_t>(data + after_events) : 0;
  frame.frame_height = has_frame_size ? get<std::uint16_t>(data + after_events + 2) : 0;
  frame.events.clear();
  for (std::uint64_t i = 0; i < event_count; ++i) {
    frame.events.push_back(
        read_event(data + message::header_extended_size + i * event_length, frame.pts_ns));
  }
  frame.tracks.clear();
  const std::uint8_t* record = data + header_length;
  for (std::uint64_t i = 0; i < track_count; ++i) {
    frame.tracks.push_back(read_track(record));  // reuses capacity: no allocation once grown
    record += record_length;
  }
  return DecodeError::none;
}

}  // namespace rtmot::messages
