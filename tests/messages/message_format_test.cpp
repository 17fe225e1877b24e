// Round trips of the binary track message on realistic frames, its byte layout and its limits.
#include "messages/message_format.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "message_test_data.hpp"

namespace rtmot::messages {
namespace {

using test::crowd_from_detections;
using test::frames_from_detections;
using test::same_as_sent;

std::vector<std::uint8_t> encode(const FrameResult& frame,
                                 std::size_t capacity = message::safe_udp_payload) {
  std::vector<std::uint8_t> buffer(capacity);
  MessageEncoder encoder;
  buffer.resize(encoder.encode(frame, buffer.data(), buffer.size()));
  return buffer;
}

TEST(MessageFormat, EveryFrameOfRealSequencesRoundTrips) {
  MessageEncoder encoder;
  DecodedMessage decoded;
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  std::size_t frames_seen = 0;
  for (const char* sequence : {"TUD-Campus", "ETH-Bahnhof", "Venice-2"}) {
    const auto frames = frames_from_detections(sequence, 200);
    ASSERT_FALSE(frames.empty()) << sequence;
    for (const auto& frame : frames) {
      const std::size_t size = encoder.encode(frame, buffer.data(), buffer.size());
      ASSERT_EQ(size, message::encoded_size(frame.tracks.size()));
      ASSERT_EQ(decode_message(buffer.data(), size, decoded), DecodeError::none);
      ASSERT_TRUE(same_as_sent(frame, decoded));
      EXPECT_EQ(decoded.latency_ns(), frame.times.sent_ns - frame.times.captured_ns);
      ++frames_seen;
    }
  }
  EXPECT_GT(frames_seen, 400U);
}

TEST(MessageFormat, FrameWithoutTracksIsTheBareHeader) {
  FrameResult frame = frames_from_detections("TUD-Campus", 1).at(0);
  frame.tracks.clear();
  const auto bytes = encode(frame);
  EXPECT_EQ(bytes.size(), message::min_size);
  DecodedMessage decoded;
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
  EXPECT_TRUE(same_as_sent(frame, decoded));
}

TEST(MessageFormat, HeaderIsLittleEndianAsDocumented) {
  FrameResult frame = frames_from_detections("TUD-Campus", 3).at(2);
  frame.stream_id = 0x0A0B0C0D;
  frame.sequence = 0x0102030405060708ULL;
  const auto bytes = encode(frame);
  ASSERT_GE(bytes.size(), message::min_size);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "RTMT");
  EXPECT_EQ(bytes[4], 1);                   // version
  EXPECT_EQ(bytes[5], 0);                   // flags
  EXPECT_EQ(bytes[6] | bytes[7] << 8, 64);  // header length
  EXPECT_EQ(bytes[8], 0x0D);                // stream id, least significant byte first
  EXPECT_EQ(bytes[11], 0x0A);
  EXPECT_EQ(bytes[16], 0x08);  // sequence
  EXPECT_EQ(bytes[23], 0x01);
  EXPECT_EQ(bytes[56] | bytes[57] << 8, static_cast<int>(frame.tracks.size()));  // tracks sent
  EXPECT_EQ(bytes[60] | bytes[61] << 8, 32);  // track record length
}

TEST(MessageFormat, TrackLimitPerSafeDatagramIsSentWhole) {
  const std::size_t limit = message::tracks_that_fit(message::safe_udp_payload);
  EXPECT_EQ(limit, 35U);
  EXPECT_EQ(message::tracks_that_fit(message::ethernet_udp_payload), 43U);
  const FrameResult crowd = crowd_from_detections("ETH-Bahnhof", limit);
  const auto bytes = encode(crowd);
  EXPECT_LE(bytes.size(), message::safe_udp_payload);
  DecodedMessage decoded;
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
  EXPECT_TRUE(same_as_sent(crowd, decoded));
}

TEST(MessageFormat, BeyondTheLimitTheHighestScoresAreSentInTrackerOrder) {
  const std::size_t limit = message::tracks_that_fit(message::safe_udp_payload);
  for (const std::size_t count : {limit + 1, 3 * limit}) {
    const FrameResult crowd = crowd_from_detections("ETH-Bahnhof", count);
    const auto bytes = encode(crowd);
    EXPECT_LE(bytes.size(), message::safe_udp_payload);
    DecodedMessage decoded;
    ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
    EXPECT_TRUE(decoded.truncated());
    EXPECT_EQ(decoded.total_track_count, count);
    ASSERT_EQ(decoded.frame.tracks.size(), limit);

    std::vector<float> scores;
    for (const auto& track : crowd.tracks) scores.push_back(track.score);
    std::sort(scores.begin(), scores.end(), std::greater<>());
    const float lowest_kept = scores[limit - 1];
    std::int32_t previous_id = 0;
    for (const auto& track : decoded.frame.tracks) {
      EXPECT_GE(track.score, lowest_kept) << "track " << track.id;
      EXPECT_GT(track.id, previous_id) << "kept tracks must stay in the tracker's order";
      previous_id = track.id;
      const auto original = std::find_if(crowd.tracks.begin(), crowd.tracks.end(),
                                         [&](const auto& t) { return t.id == track.id; });
      ASSERT_NE(original, crowd.tracks.end());
      EXPECT_EQ(original->box.x, track.box.x);
      EXPECT_EQ(original->score, track.score);
    }
  }
}

TEST(MessageFormat, LargerBufferCarriesLargerCrowdsWhole) {
  const FrameResult crowd = crowd_from_detections("ETH-Bahnhof", 500);
  const auto bytes = encode(crowd, message::max_message_size);
  EXPECT_EQ(bytes.size(), message::encoded_size(500));
  DecodedMessage decoded;
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
  EXPECT_TRUE(same_as_sent(crowd, decoded));
}

TEST(MessageFormat, NarrowFieldsSaturateAndSpecialValuesSurvive) {
  FrameResult frame = frames_from_detections("TUD-Campus", 1).at(0);
  ASSERT_GE(frame.tracks.size(), 3U);
  frame.tracks[0].class_id = -1;  // "unknown" as replayed files say
  frame.tracks[0].hits = 70'000;  // more than 16 bits: saturates
  frame.tracks[0].age = std::numeric_limits<std::int32_t>::max();
  frame.tracks[1].score = std::numeric_limits<float>::quiet_NaN();
  frame.tracks[1].box.x = -12.25F;  // a coasting box leaving the image
  frame.tracks[2].class_id = 40'000;
  const auto bytes = encode(frame);
  DecodedMessage decoded;
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
  const auto& tracks = decoded.frame.tracks;
  EXPECT_EQ(tracks[0].class_id, -1);
  EXPECT_EQ(tracks[0].hits, 65'535);
  EXPECT_EQ(tracks[0].age, std::numeric_limits<std::int32_t>::max());
  EXPECT_TRUE(std::isnan(tracks[1].score));
  EXPECT_EQ(tracks[1].box.x, -12.25F);
  EXPECT_EQ(tracks[2].class_id, 32'767);
}

TEST(MessageFormat, LaterMinorVersionWithLongerHeaderAndRecordsStillDecodes) {
  // The versioning rule: fields are added at the end of the header or of a track record and
  // announced by the length fields; a version-1 reader skips what it does not know.
  const FrameResult frame = frames_from_detections("ETH-Bahnhof", 5).at(4);
  const auto v1 = encode(frame);
  const std::size_t extra_header = 8;
  const std::size_t extra_record = 4;
  std::vector<std::uint8_t> longer(v1.begin(), v1.begin() + 64);
  longer.insert(longer.end(), extra_header, 0xEE);
  for (std::size_t i = 0; i < frame.tracks.size(); ++i) {
    const auto record = v1.begin() + 64 + static_cast<std::ptrdiff_t>(32 * i);
    longer.insert(longer.end(), record, record + 32);
    longer.insert(longer.end(), extra_record, 0xDD);
  }
  longer[6] = 64 + extra_header;
  longer[60] = 32 + extra_record;
  const std::uint32_t crc =
      static_cast<std::uint32_t>(::crc32(0L, longer.data(), static_cast<uInt>(longer.size())));
  for (int i = 0; i < 4; ++i) longer.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));

  DecodedMessage decoded;
  ASSERT_EQ(decode_message(longer.data(), longer.size(), decoded), DecodeError::none);
  EXPECT_TRUE(same_as_sent(frame, decoded));
}

TEST(MessageFormat, DecodingReusesTrackStorage) {
  const auto frames = frames_from_detections("ETH-Bahnhof", 50);
  const auto busiest = std::max_element(
      frames.begin(), frames.end(),
      [](const auto& a, const auto& b) { return a.tracks.size() < b.tracks.size(); });
  DecodedMessage decoded;
  const auto big = encode(*busiest);
  ASSERT_EQ(decode_message(big.data(), big.size(), decoded), DecodeError::none);
  const auto* storage = decoded.frame.tracks.data();
  for (const auto& frame : frames) {
    const auto bytes = encode(frame);
    ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
    EXPECT_EQ(decoded.frame.tracks.data(), storage);
  }
}

TEST(MessageFormat, EncoderRefusesABufferSmallerThanTheHeader) {
  const FrameResult frame = frames_from_detections("TUD-Campus", 1).at(0);
  std::vector<std::uint8_t> buffer(message::min_size - 1);
  MessageEncoder encoder;
  EXPECT_EQ(encoder.encode(frame, buffer.data(), buffer.size()), 0U);
}

}  // namespace
}  // namespace rtmot::messages
