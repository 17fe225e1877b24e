// The decoder against damaged and hostile input: every damage is reported, nothing crashes.
// (Run under the address/undefined sanitizers, these also show it never reads out of bounds.)
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <random>
#include <vector>

#include "message_test_data.hpp"
#include "messages/message_format.hpp"

namespace rtmot::messages {
namespace {

// The busiest of ETH-Bahnhof's first 100 frames: every field, and several tracks, to damage.
std::vector<std::uint8_t> realistic_message() {
  const auto frames = test::frames_from_detections("ETH-Bahnhof", 100);
  if (frames.empty()) return {};
  const auto busiest = std::max_element(
      frames.begin(), frames.end(),
      [](const auto& a, const auto& b) { return a.tracks.size() < b.tracks.size(); });
  std::vector<std::uint8_t> bytes(message::safe_udp_payload);
  MessageEncoder encoder;
  bytes.resize(encoder.encode(*busiest, bytes.data(), bytes.size()));
  return bytes;
}

// Rewrites the CRC so that a test reaches the check it means to reach.
void reseal(std::vector<std::uint8_t>& bytes) {
  const std::size_t body = bytes.size() - 4;
  const auto crc = static_cast<std::uint32_t>(::crc32(0L, bytes.data(), static_cast<uInt>(body)));
  for (int i = 0; i < 4; ++i)
    bytes[body + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (8 * i));
}

DecodeError decode(const std::vector<std::uint8_t>& bytes) {
  DecodedMessage decoded;
  return decode_message(bytes.data(), bytes.size(), decoded);
}

TEST(MessageCorruption, EverySingleBitFlipIsDetected) {
  auto bytes = realistic_message();
  ASSERT_GE(bytes.size(), message::encoded_size(8));
  ASSERT_EQ(decode(bytes), DecodeError::none);
  for (std::size_t bit = 0; bit < bytes.size() * 8; ++bit) {
    bytes[bit / 8] ^= static_cast<std::uint8_t>(1U << (bit % 8));
    EXPECT_NE(decode(bytes), DecodeError::none)
        << "flip of bit " << bit % 8 << " of byte " << bit / 8;
    bytes[bit / 8] ^= static_cast<std::uint8_t>(1U << (bit % 8));
  }
}

TEST(MessageCorruption, EveryTruncationAndAnyExtraByteIsDetected) {
  const auto bytes = realistic_message();
  ASSERT_FALSE(bytes.empty());
  DecodedMessage decoded;
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    // A copy of exactly `size` bytes, so that the sanitizers catch any read past it.
    const std::vector<std::uint8_t> cut(bytes.begin(),
                                        bytes.begin() + static_cast<std::ptrdiff_t>(size));
    const DecodeError error = decode_message(cut.data(), cut.size(), decoded);
    EXPECT_NE(error, DecodeError::none) << "cut to " << size << " bytes";
  }
  auto padded = bytes;
  padded.push_back(0);
  EXPECT_EQ(decode(padded), DecodeError::length_mismatch);
  EXPECT_EQ(decode_message(nullptr, 0, decoded), DecodeError::too_short);
}

TEST(MessageCorruption, EachStructuralCheckNamesItsReason) {
  const auto good = realistic_message();
  ASSERT_FALSE(good.empty());

  auto bytes = good;
  bytes[0] = 'X';
  EXPECT_EQ(decode(bytes), DecodeError::bad_magic);

  bytes = good;
  bytes[4] = 2;  // a newer, incompatible version, correctly sealed
  reseal(bytes);
  EXPECT_EQ(decode(bytes), DecodeError::unsupported_version);

  bytes = good;
  bytes[6] = 63;
  reseal(bytes);
  EXPECT_EQ(decode(bytes), DecodeError::bad_header_length);

  bytes = good;
  bytes[6] = 0xFF;
  bytes[7] = 0xFF;  // past the end
  reseal(bytes);
  EXPECT_EQ(decode(bytes), DecodeError::bad_header_length);

  bytes = good;
  bytes[60] = 31;
  reseal(bytes);
  EXPECT_EQ(decode(bytes), DecodeError::bad_track_record_length);

  bytes = good;
  bytes[56] = static_cast<std::uint8_t>(bytes[58] + 1);  // more sent than the frame had
  reseal(bytes);
  EXPECT_EQ(decode(bytes), DecodeError::bad_track_counts);

  bytes = good;
  bytes[56] = static_cast<std::uint8_t>(bytes[56] - 1);
  reseal(bytes);
  EXPECT_EQ(decode(bytes), DecodeError::length_mismatch);

  bytes = good;
  bytes[100] ^= 0x40;
  EXPECT_EQ(decode(bytes), DecodeError::bad_crc);
}

TEST(MessageCorruption, RandomBytesNeverDecodeAndNeverCrash) {
  std::mt19937 random(20261122);
  const auto good = realistic_message();
  ASSERT_FALSE(good.empty());
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> length(0, 2 * good.size());
  for (int trial = 0; trial < 20'000; ++trial) {
    std::vector<std::uint8_t> bytes(length(random));
    for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(random));
    // Half the trials get a valid magic and version so that the deeper checks are reached.
    if (trial % 2 == 0 && bytes.size() >= 8)
      std::copy(good.begin(), good.begin() + 8, bytes.begin());
    EXPECT_NE(decode(bytes), DecodeError::none) << "trial " << trial;
  }
}

}  // namespace
}  // namespace rtmot::messages
