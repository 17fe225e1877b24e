#pragma once
// The compact binary track message: one per processed frame, little-endian, versioned,
// CRC32-checked. Byte layout, versioning rule and size formula: docs/message-format.md (keep both
// in step).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "messages/frame_result.hpp"

namespace rtmot::messages {

namespace message {

constexpr std::uint32_t magic = 0x544D5452;  // bytes "RTMT" on the wire
constexpr std::uint8_t version = 1;
constexpr std::size_t header_size = 64;        // version 1's header; a later header may be longer
constexpr std::size_t track_record_size = 32;  // version 1's track record; later ones may be longer
constexpr std::size_t crc_size = 4;
/// The header extension (still version 1: old readers skip it with the header): run id, then the
/// events. Present when a message carries a run id or events; the header is then
/// header_extended_size + event_count x event_record_size bytes long.
constexpr std::size_t header_extended_size = 80;
constexpr std::size_t event_record_size = 24;
/// After the events, inside the header still: the frame's width and height (u16 each), when the
/// sender knows them. A reader finds them at header_extended_size + event_count x
/// event_record_length when the header holds that many more bytes.
constexpr std::size_t frame_size_size = 4;
constexpr std::size_t min_size = header_size + crc_size;
/// Past this many tracks the 16-bit counts saturate (documented; real scenes are far below).
constexpr std::size_t max_track_count = 0xFFFF;

/// Flag bits of byte 5. Bits not listed are 0 when sent and ignored when read.
constexpr std::uint8_t flag_truncated =
    0x01;  // fewer tracks than the frame had: highest scores kept
constexpr std::uint8_t flag_source_outage = 0x02;     // no picture: the source is being reopened
constexpr std::uint8_t flag_events_truncated = 0x04;  // fewer events than the frame had
constexpr std::uint8_t flag_end_of_stream = 0x08;     // the stream's last message (no tracks)
constexpr std::uint8_t flag_predicted = 0x10;  // a skipped frame: the tracks' predicted boxes
/// With flag_predicted: the boxes were followed in the image (a track's score is how well: 0 for
/// one the image lost, whose box is its prediction). docs/full-rate.md, "Observed boxes".
constexpr std::uint8_t flag_observed = 0x20;

/// The largest UDP payload we send by default: fits one unfragmented datagram on any IPv6 path
/// (1280-byte minimum MTU - 40 IPv6 - 8 UDP = 1232) and through VPN/tunnel overheads; see the doc.
constexpr std::size_t safe_udp_payload = 1200;
/// Ethernet's 1500-byte MTU - 20 IPv4 - 8 UDP: the most one unfragmented IPv4 datagram can carry.
constexpr std::size_t ethernet_udp_payload = 1472;
/// Framing limit of the binary file: a length prefix above this is corruption, not a message.
constexpr std::size_t max_message_size = 65507;  // the largest UDP payload over IPv4

constexpr std::size_t encoded_size(std::size_t track_count) {
  return header_size + track_record_size * track_count + crc_size;
}

/// How many tracks fit in `capacity` bytes (0 if not even the header fits).
constexpr std::size_t tracks_that_fit(std::size_t capacity) {
  if (capacity < min_size) return 0;
  const std::size_t fit = (capacity - min_size) / track_record_size;
  return fit < max_track_count ? fit : max_track_count;
}

}  // namespace message

/// Writes messages into a caller's buffer. Keeps scratch space for choosing the tracks to keep
/// when they do not all fit, so that encoding allocates nothing once it has seen the scene's size.
class MessageEncoder {
 public:
  /// Encodes `result` into `buffer[0, capacity)` and returns the bytes written. When not every
  /// track fits, keeps the highest-score ones (in their original order), sets flag_truncated and
  /// records the frame's full track count. Events go first (rare and what a ground station counts);
  /// those that do not fit are dropped and flag_events_truncated set. Returns 0 only if
  /// `capacity` < message::min_size.
  std::size_t encode(const FrameResult& result, std::uint8_t* buffer, std::size_t capacity);

 private:
  std::vector<std::uint32_t> order_;  // indices into result.tracks, reused between frames
};

enum class DecodeError : std::uint8_t {
  none = 0,
  too_short,            // fewer bytes than the smallest message
  bad_magic,            // not one of our messages
  unsupported_version,  // a version this reader does not know (the reader is older)
  bad_header_length,    // header length below version 1's or past the end
  bad_track_record_length,
  bad_track_counts,  // sent track count above the frame's total
  length_mismatch,   // size differs from what the header announces (truncated or padded)
  bad_crc,           // the bytes changed on the way
  bad_event_counts,  // the header extension's events do not fit in the header
};
constexpr std::size_t decode_error_count = 10;

std::string_view to_string(DecodeError error);

/// A received message: the frame as the sender had it, as far as the message carries it.
/// Carried in `frame`: stream_id, sequence, frame_number, pts_ns, frames_dropped,
/// times.captured_ns, times.sent_ns (= captured + latency) and the tracks; the other times are 0.
struct DecodedMessage {
  FrameResult frame;
  std::uint8_t version{0};
  std::uint8_t flags{0};
  std::uint32_t total_track_count{0};  // tracks the frame had; > frame.tracks.size() if truncated
  bool events_truncated() const { return (flags & message::flag_events_truncated) != 0; }

  bool truncated() const { return (flags & message::flag_truncated) != 0; }
  std::int64_t latency_ns() const { return frame.times.sent_ns - frame.times.captured_ns; }
};

/// Decodes one message from untrusted bytes. Checks every length and count against `size` before
/// reading, then magic, version and CRC; never throws (tracks reuse `out`'s storage: no allocation
/// once it has grown), never reads outside [data, data + size). On error `out` is unspecified.
DecodeError decode_message(const std::uint8_t* data, std::size_t size, DecodedMessage& out);

}  // namespace rtmot::messages
