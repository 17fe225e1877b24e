// The header extension (run id, events): round trips in binary and JSON, what an old reader sees,
// events that do not fit, and a restarted sender told by its run id.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <string>
#include <vector>

#include "events/event_counter.hpp"
#include "message_test_data.hpp"
#include "messages/json_line_decoder.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/message_format.hpp"
#include "messages/message_stream_stats.hpp"

namespace rtmot::messages {
namespace {

// Frames of PETS09-S2L1's detections with the events a counter decides on them: a vertical line
// through the middle and a zone over the left half (the detections' ids are unique per box, so
// every event here is a zone enter or a loss; enough to carry real values).
std::vector<FrameResult> frames_with_events() {
  auto frames = test::frames_from_detections("PETS09-S2L1", 120);
  events::EventsConfig config;
  config.lines.push_back({"middle", {{384.0, 0.0}, {384.0, 576.0}}, true});
  config.zones.push_back({"left", {{0, 0}, {384, 0}, {384, 576}, {0, 576}}, 0.0});
  config.lost_after_seconds = 0.2;
  events::EventCounter counter(config);
  for (auto& frame : frames) {
    frame.run_id = 0x0123456789abcdefULL;
    const auto& decided = counter.update(frame.tracks, static_cast<double>(frame.pts_ns) * 1e-9);
    frame.events.assign(decided.begin(), decided.end());
  }
  return frames;
}

void expect_same_events(const FrameResult& sent, const FrameResult& got) {
  ASSERT_EQ(got.events.size(), sent.events.size());
  for (std::size_t i = 0; i < sent.events.size(); ++i) {
    const auto& a = sent.events[i];
    const auto& b = got.events[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.track_id, b.track_id);
    EXPECT_EQ(a.class_id, b.class_id);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.lost, b.lost);
    EXPECT_NEAR(a.dwell_seconds, b.dwell_seconds, 0.0005);
    EXPECT_NEAR(b.time, static_cast<double>(sent.pts_ns) * 1e-9, 1e-9);
  }
}

// `frame` written as a JSON line (into `line`) and read back (into `decoded`).
::testing::AssertionResult through_json(const FrameResult& frame, fmt::memory_buffer& line,
                                        DecodedMessage& decoded) {
  line.clear();
  append_json_line(frame, static_cast<std::uint32_t>(frame.tracks.size()), false,
                   JsonLineExtras{1, nullptr}, line);
  std::string problem;
  if (!decode_json_line(reinterpret_cast<const std::uint8_t*>(line.data()), line.size(), decoded,
                        problem)) {
    return ::testing::AssertionFailure() << problem;
  }
  return ::testing::AssertionSuccess();
}

TEST(MessageEvents, RunIdAndEventsRoundTripAndOldReadersFindTheTracksWhereTheyWere) {
  const auto frames = frames_with_events();
  MessageEncoder encoder;
  DecodedMessage decoded;
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  std::size_t events_seen = 0;
  for (const auto& frame : frames) {
    const std::size_t size = encoder.encode(frame, buffer.data(), buffer.size());
    ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
    ASSERT_TRUE(test::same_as_sent(frame, decoded));
    EXPECT_EQ(decoded.frame.run_id, frame.run_id);
    expect_same_events(frame, decoded.frame);
    // What a version-1 reader of before the extension does: skip header_length bytes, read the
    // tracks, check the size. The extension lives inside the header, so nothing moved for it.
    const std::size_t header_length = buffer[6] | (buffer[7] << 8);
    EXPECT_EQ(header_length,
              message::header_extended_size + frame.events.size() * message::event_record_size);
    EXPECT_EQ(size,
              header_length + frame.tracks.size() * message::track_record_size + message::crc_size);
    events_seen += frame.events.size();
  }
  EXPECT_GT(events_seen, 50U);
}

// The frame size (a ground station's canvas) rides after the events, inside the header: it round
// trips in binary and JSON, and a reader of before it finds the events and tracks where they were.
TEST(MessageFrameSize, RoundTripsAfterTheEventsAndOlderReadersSkipIt) {
  auto frames = frames_with_events();
  MessageEncoder encoder;
  DecodedMessage decoded;
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  fmt::memory_buffer line;
  for (auto& frame : frames) {
    frame.frame_width = 768;
    frame.frame_height = 576;
    const std::size_t size = encoder.encode(frame, buffer.data(), buffer.size());
    ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
    ASSERT_TRUE(test::same_as_sent(frame, decoded));
    expect_same_events(frame, decoded.frame);
    EXPECT_EQ(decoded.frame.frame_width, 768);
    EXPECT_EQ(decoded.frame.frame_height, 576);
    const std::size_t header_length = buffer[6] | (buffer[7] << 8);
    EXPECT_EQ(header_length, message::header_extended_size +
                                 frame.events.size() * message::event_record_size +
                                 message::frame_size_size);
    ASSERT_TRUE(through_json(frame, line, decoded));
    EXPECT_EQ(decoded.frame.frame_width, 768);
    EXPECT_EQ(decoded.frame.frame_height, 576);
  }
  // Unknown: not sent, read back as 0.
  frames.front().frame_width = 0;
  const std::size_t size = encoder.encode(frames.front(), buffer.data(), buffer.size());
  ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
  EXPECT_EQ(decoded.frame.frame_width, 0);
  EXPECT_EQ(decoded.frame.frame_height, 0);
}

TEST(MessageEvents, AMessageWithoutRunIdOrEventsIsUnchanged) {
  FrameResult frame = test::frames_from_detections("TUD-Campus", 1).at(0);
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  MessageEncoder encoder;
  EXPECT_EQ(encoder.encode(frame, buffer.data(), buffer.size()),
            message::encoded_size(frame.tracks.size()));
}

TEST(MessageEvents, EventsGoFirstWhenTheDatagramIsFullAndSaySoWhenCut) {
  FrameResult frame = test::crowd_from_detections("ETH-Bahnhof", 40);
  frame.run_id = 7;
  events::Event event;
  event.kind = events::EventKind::zone_enter;
  frame.events.assign(45, event);
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  MessageEncoder encoder;
  DecodedMessage decoded;
  const std::size_t size = encoder.encode(frame, buffer.data(), buffer.size());
  ASSERT_LE(size, message::safe_udp_payload);
  ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
  // (1200 - 80 - 4) / 24 = 46 events fit: all 45 kept, tracks take the rest.
  EXPECT_EQ(decoded.frame.events.size(), 45U);
  EXPECT_FALSE(decoded.events_truncated());
  EXPECT_EQ(decoded.frame.tracks.size(), (1200U - 80U - 45U * 24U - 4U) / 32U);
  EXPECT_TRUE(decoded.truncated());
  frame.events.assign(60, event);
  const std::size_t cut = encoder.encode(frame, buffer.data(), buffer.size());
  ASSERT_EQ(decode_message(buffer.data(), cut, decoded), DecodeError::none);
  EXPECT_EQ(decoded.frame.events.size(), 46U);
  EXPECT_TRUE(decoded.events_truncated());
}

TEST(MessageEvents, EventCountsThatDoNotFitTheHeaderAreCorrupt) {
  FrameResult frame = test::frames_from_detections("TUD-Campus", 1).at(0);
  frame.events.resize(2);
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  MessageEncoder encoder;
  const std::size_t size = encoder.encode(frame, buffer.data(), buffer.size());
  buffer[72] = 3;  // three events announced, two carried
  buffer[76] = 3;
  // Recompute the CRC so that the count itself is what the reader catches.
  const std::uint32_t crc = static_cast<std::uint32_t>(::crc32(0L, buffer.data(), size - 4));
  for (int i = 0; i < 4; ++i) buffer[size - 4 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  DecodedMessage decoded;
  EXPECT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::bad_event_counts);
}

TEST(MessageEvents, JsonLinesCarryTheRunAndTheEvents) {
  const auto frames = frames_with_events();
  fmt::memory_buffer line;
  DecodedMessage decoded;
  std::size_t with_events = 0;
  for (const auto& frame : frames) {
    ASSERT_TRUE(through_json(frame, line, decoded));
    EXPECT_EQ(decoded.frame.run_id, frame.run_id);
    expect_same_events(frame, decoded.frame);
    if (!frame.events.empty()) {
      ++with_events;
      EXPECT_NE(std::string(line.data(), line.size()).find(R"("run":"0123456789abcdef")"),
                std::string::npos);
    }
  }
  EXPECT_GT(with_events, 10U);
}

// The stream's last message: the counter's finish() events (tracks still inside the zone leave it,
// marked lost) with no tracks, flagged end_of_stream, in binary (flag bit 3) and in JSON lines;
// every other message says it is not the end.
TEST(MessageEvents, TheEndOfAStreamCarriesTheFinishEventsInBinaryAndJson) {
  auto frames = test::frames_from_detections("PETS09-S2L1", 60);
  events::EventsConfig config;
  config.zones.push_back({"left", {{0, 0}, {384, 0}, {384, 576}, {0, 576}}, 0.0});
  events::EventCounter counter(config);
  for (const auto& frame : frames)
    (void)counter.update(frame.tracks, static_cast<double>(frame.pts_ns) * 1e-9);
  FrameResult end = frames.back();
  const auto& finished = counter.finish(static_cast<double>(end.pts_ns) * 1e-9);
  ASSERT_FALSE(finished.empty());
  end.tracks.clear();
  end.events.assign(finished.begin(), finished.end());
  end.sequence += 1;
  end.end_of_stream = true;
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  DecodedMessage decoded;
  MessageEncoder encoder;
  for (const FrameResult* sent : {&frames.back(), &end}) {
    const std::size_t size = encoder.encode(*sent, buffer.data(), buffer.size());
    ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
    EXPECT_EQ(decoded.frame.end_of_stream, sent->end_of_stream);
    EXPECT_EQ((buffer[5] & message::flag_end_of_stream) != 0, sent->end_of_stream);
    expect_same_events(*sent, decoded.frame);
    fmt::memory_buffer line;
    append_json_line(*sent, static_cast<std::uint32_t>(sent->tracks.size()), false,
                     JsonLineExtras{1, nullptr}, line);
    std::string problem;
    ASSERT_TRUE(decode_json_line(reinterpret_cast<const std::uint8_t*>(line.data()), line.size(),
                                 decoded, problem))
        << problem;
    EXPECT_EQ(decoded.frame.end_of_stream, sent->end_of_stream);
    expect_same_events(*sent, decoded.frame);
  }
  for (const auto& event : end.events) {
    EXPECT_EQ(event.kind, events::EventKind::zone_exit);
    EXPECT_TRUE(event.lost);
  }
  EXPECT_EQ(counter.zone_counts()[0].occupancy, 0);
}

// Full-rate output (docs/full-rate.md): a skipped frame's message with the predicted boxes is
// flagged in binary (flag bit 4) and JSON lines ("predicted":true) and reads back as predicted;
// a processed frame's says nothing of it (its bytes are those of a sender without the option).
TEST(MessagePredicted, APredictedFrameIsFlaggedInBinaryAndJson) {
  const auto frames = test::frames_from_detections("PETS09-S2L1", 20);
  FrameResult processed = frames.back();
  ASSERT_FALSE(processed.tracks.empty());
  FrameResult predicted = processed;
  predicted.predicted = true;
  predicted.sequence += 1;
  predicted.frame_number += 1;
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  std::vector<std::uint8_t> unflagged(message::safe_udp_payload);
  DecodedMessage decoded;
  MessageEncoder encoder;
  for (const FrameResult* sent : {&processed, &predicted}) {
    const std::size_t size = encoder.encode(*sent, buffer.data(), buffer.size());
    ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
    EXPECT_EQ(decoded.frame.predicted, sent->predicted);
    EXPECT_EQ(buffer[5], sent->predicted ? message::flag_predicted : 0);
    EXPECT_EQ(decoded.frame.tracks.size(), sent->tracks.size());
    // Apart from the flag (and so the CRC), the same bytes as the frame sent unflagged.
    FrameResult plain = *sent;
    plain.predicted = false;
    ASSERT_EQ(encoder.encode(plain, unflagged.data(), unflagged.size()), size);
    EXPECT_TRUE(std::equal(buffer.begin() + 6, buffer.begin() + static_cast<long>(size) - 4,
                           unflagged.begin() + 6));
    fmt::memory_buffer line;
    append_json_line(*sent, static_cast<std::uint32_t>(sent->tracks.size()), false,
                     JsonLineExtras{1, nullptr}, line);
    const std::string text(line.data(), line.size());
    EXPECT_EQ(text.find(R"("predicted":true)") != std::string::npos, sent->predicted);
    EXPECT_EQ(text.find("predicted") != std::string::npos, sent->predicted);
    std::string problem;
    ASSERT_TRUE(decode_json_line(reinterpret_cast<const std::uint8_t*>(line.data()), line.size(),
                                 decoded, problem))
        << problem;
    EXPECT_EQ(decoded.frame.predicted, sent->predicted);
    EXPECT_EQ((decoded.flags & message::flag_predicted) != 0, sent->predicted);
  }
  // rtmot listen counts them apart, and as ordinary messages of the stream (no loss, no clash).
  ListenerStats stats;
  for (const FrameResult* sent : {&processed, &predicted}) {
    const std::size_t size = encoder.encode(*sent, buffer.data(), buffer.size());
    ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
    stats.record(decoded);
  }
  const StreamStats& stream = stats.streams().at(processed.stream_id);
  EXPECT_EQ(stream.messages, 2U);
  EXPECT_EQ(stream.predicted, 1U);
  EXPECT_EQ(stream.sequences.lost(), 0U);
  EXPECT_EQ(stream.sequences.clashes(), 0U);
}

// Following the image (docs/full-rate.md, "Observed boxes"): a skipped frame whose boxes the image
// followed carries flag bit 5 with bit 4, and "observed":true in JSON lines; a processed frame
// cannot be observed (the flag is only read and written beside predicted).
TEST(MessageObserved, AnObservedFrameIsFlaggedInBinaryAndJsonAndOnlyWithPredicted) {
  const auto frames = test::frames_from_detections("PETS09-S2L1", 20);
  FrameResult observed = frames.back();
  ASSERT_FALSE(observed.tracks.empty());
  observed.predicted = true;
  observed.observed = true;
  FrameResult processed = frames.back();
  processed.observed = true;  // meaningless without predicted: never sent
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  DecodedMessage decoded;
  MessageEncoder encoder;
  for (const FrameResult* sent : {&observed, &processed}) {
    const bool flagged = sent->predicted;
    const std::size_t size = encoder.encode(*sent, buffer.data(), buffer.size());
    ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
    EXPECT_EQ(decoded.frame.observed, flagged);
    EXPECT_EQ(buffer[5],
              flagged ? message::flag_predicted | message::flag_observed : std::uint8_t{0});
    fmt::memory_buffer line;
    append_json_line(*sent, static_cast<std::uint32_t>(sent->tracks.size()), false,
                     JsonLineExtras{1, nullptr}, line);
    const std::string text(line.data(), line.size());
    EXPECT_EQ(text.find(R"("observed":true)") != std::string::npos, flagged);
    std::string problem;
    ASSERT_TRUE(decode_json_line(reinterpret_cast<const std::uint8_t*>(line.data()), line.size(),
                                 decoded, problem))
        << problem;
    EXPECT_EQ(decoded.frame.observed, flagged);
    EXPECT_EQ((decoded.flags & message::flag_observed) != 0, flagged);
  }
}

TEST(SequenceAccounting, ABoardRestartedWithinTheWindowIsARestartByItsRunId) {
  SequenceAccounting accounting;
  for (std::uint64_t s = 0; s < 71; ++s)
    accounting.record(s, 1000 + static_cast<std::int64_t>(s), 11);
  // The board reboots: sequence 0 again, a new run id, its clock started again too.
  EXPECT_EQ(accounting.record(0, 5, 22), Arrival::restart);
  for (std::uint64_t s = 1; s < 71; ++s)
    EXPECT_EQ(accounting.record(s, 5 + static_cast<std::int64_t>(s), 22), Arrival::in_order);
  EXPECT_EQ(accounting.duplicated(), 0U);
  EXPECT_EQ(accounting.restarts(), 1U);
  EXPECT_EQ(accounting.lost(), 0U);
  // A message of the first run after the restart: another sender on this stream id.
  EXPECT_EQ(accounting.record(71, 1071, 11), Arrival::clash);
}

TEST(SequenceAccounting, WithoutARunIdTheSameRestartLooksLikeDuplicates) {
  // What the extension fixes: senders before it (run id 0) restarted within 4096 messages.
  SequenceAccounting accounting;
  for (std::uint64_t s = 0; s < 71; ++s) accounting.record(s);
  for (std::uint64_t s = 0; s < 71; ++s) accounting.record(s);
  EXPECT_EQ(accounting.duplicated(), 71U);
  EXPECT_EQ(accounting.restarts(), 0U);
}

TEST(ListenerStats, CountsEventsPerKindAndIndex) {
  const auto frames = frames_with_events();
  ListenerStats stats;
  std::uint64_t sent = 0;
  DecodedMessage message;
  for (const auto& frame : frames) {
    message.frame = frame;
    stats.record(message);
    sent += frame.events.size();
  }
  std::uint64_t counted = 0;
  const EventTally& events = stats.streams().begin()->second.events;
  for (const auto& entry : events.listed()) counted += entry.second;
  EXPECT_EQ(counted, sent);
  EXPECT_EQ(events.unlisted(), 0U);
}

// A spoofed stream may name any of 16.7 M (kind, index) pairs: the first EventTally::max_pairs
// are listed, the events of later pairs counted together, none lost.
TEST(ListenerStats, EventPairsOfOneStreamAreBoundedAndTheRestCounted) {
  ListenerStats stats;
  DecodedMessage message;
  message.frame.stream_id = 9;
  const std::size_t pairs = 3 * EventTally::max_pairs;
  std::uint64_t sent = 0;
  for (std::size_t m = 0; m < pairs / 64; ++m) {
    message.frame.sequence = m;
    message.frame.pts_ns = static_cast<std::int64_t>(m) * 40'000'000;
    message.frame.events.clear();
    for (std::size_t e = 0; e < 64; ++e) {
      events::Event event;
      const std::size_t pair = m * 64 + e;
      event.kind = static_cast<events::EventKind>(pair % 5);
      event.index = static_cast<std::uint16_t>(pair / 5);
      message.frame.events.push_back(event);
    }
    stats.record(message);
    sent += 64;
  }
  // Again the first pair: still counted apart.
  message.frame.sequence = pairs / 64;
  message.frame.pts_ns = static_cast<std::int64_t>(pairs / 64) * 40'000'000;
  message.frame.events.assign(1, events::Event{});
  stats.record(message);
  ++sent;
  const EventTally& events = stats.streams().at(9).events;
  EXPECT_EQ(events.listed().size(), EventTally::max_pairs);
  EXPECT_EQ(events.listed().at({0, 0}), 2U);
  EXPECT_EQ(events.unlisted(), pairs - EventTally::max_pairs);
  EXPECT_EQ(events.total(), sent);
}

}  // namespace
}  // namespace rtmot::messages
