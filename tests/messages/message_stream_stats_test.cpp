// The listener's accounting of loss, reordering and duplication on crafted arrival orders.
#include "messages/message_stream_stats.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rtmot::messages {
namespace {

std::vector<Arrival> feed(SequenceAccounting& accounting,
                          const std::vector<std::uint64_t>& sequences) {
  std::vector<Arrival> arrivals;
  for (const auto sequence : sequences) arrivals.push_back(accounting.record(sequence));
  return arrivals;
}

TEST(SequenceAccounting, GapsLateArrivalsAndDuplicates) {
  SequenceAccounting accounting;
  const auto arrivals = feed(accounting, {0, 1, 2, 4, 3, 3, 7, 5, 8});
  const std::vector<Arrival> expected = {Arrival::first,     Arrival::in_order, Arrival::in_order,
                                         Arrival::after_gap, Arrival::late,     Arrival::duplicate,
                                         Arrival::after_gap, Arrival::late,     Arrival::in_order};
  EXPECT_EQ(arrivals, expected);
  EXPECT_EQ(accounting.received(), 9U);
  EXPECT_EQ(accounting.lost(), 1U);  // 6 never came
  EXPECT_EQ(accounting.reordered(), 2U);
  EXPECT_EQ(accounting.duplicated(), 1U);
  EXPECT_EQ(accounting.restarts(), 0U);
}

TEST(SequenceAccounting, ListeningMidStreamIsNotLoss) {
  SequenceAccounting accounting;
  feed(accounting, {1000, 1001, 1003});
  EXPECT_EQ(accounting.lost(), 1U);
  // Arriving late from before the first one seen: reordered, and what lies between is lost.
  EXPECT_EQ(accounting.record(998), Arrival::late);
  EXPECT_EQ(accounting.lost(), 2U);  // 999 and 1002
  EXPECT_EQ(accounting.reordered(), 1U);
  EXPECT_EQ(accounting.record(998), Arrival::duplicate);
}

TEST(SequenceAccounting, DuplicatesAreToldFromLateArrivalsAcrossTheWindow) {
  SequenceAccounting accounting;
  const std::uint64_t window = SequenceAccounting::window;
  for (std::uint64_t s = 0; s < 2 * window + 10; ++s) {
    if (s != window + 20) accounting.record(s);  // lose one whose slot sequence 20 used
  }
  EXPECT_EQ(accounting.lost(), 1U);
  EXPECT_EQ(accounting.record(window + 20), Arrival::late);  // its slot was cleared when skipped
  EXPECT_EQ(accounting.record(2 * window + 3), Arrival::duplicate);
  EXPECT_EQ(accounting.lost(), 0U);
  EXPECT_EQ(accounting.duplicated(), 1U);
}

TEST(SequenceAccounting, ASenderThatStartsAgainIsARestartNotAFlood) {
  SequenceAccounting accounting;
  for (std::uint64_t s = 0; s < 10'000; ++s) {
    if (s != 500) accounting.record(s);
  }
  EXPECT_EQ(accounting.record(0), Arrival::restart);
  feed(accounting, {1, 2, 4});
  EXPECT_EQ(accounting.restarts(), 1U);
  EXPECT_EQ(accounting.lost(), 2U);  // 500 before the restart, 3 after it
  EXPECT_EQ(accounting.duplicated(), 0U);
  EXPECT_EQ(accounting.reordered(), 0U);
}

TEST(SequenceAccounting, LongOutageCountsEverySkippedSequence) {
  SequenceAccounting accounting;
  feed(accounting, {0, 1, 100'001, 100'002});
  EXPECT_EQ(accounting.lost(), 99'999U);
}

DecodedMessage message(std::uint32_t stream, std::uint64_t sequence, std::int64_t latency_ns) {
  DecodedMessage decoded;
  decoded.frame.stream_id = stream;
  decoded.frame.sequence = sequence;
  decoded.frame.times.captured_ns = 1'000'000'000;
  decoded.frame.times.sent_ns = decoded.frame.times.captured_ns + latency_ns;
  decoded.frame.tracks.resize(2);
  return decoded;
}

TEST(ListenerStats, StreamsAreCountedApartAndCorruptByReason) {
  ListenerStats stats;
  stats.record(message(1, 0, 10));
  stats.record(message(2, 0, 40));
  stats.record(message(1, 2, 30));
  stats.record(message(1, 2, 99));  // a duplicate: not a second latency sample
  stats.record(message(2, 1, 20));
  stats.record_corrupt(DecodeError::bad_crc);
  stats.record_corrupt(DecodeError::bad_crc);
  stats.record_corrupt(DecodeError::length_mismatch);

  ASSERT_EQ(stats.streams().size(), 2U);
  const StreamStats& one = stats.streams().at(1);
  EXPECT_EQ(one.sequences.received(), 3U);
  EXPECT_EQ(one.sequences.lost(), 1U);
  EXPECT_EQ(one.sequences.duplicated(), 1U);
  EXPECT_EQ(one.messages, 2U);
  EXPECT_EQ(one.tracks, 4U);
  EXPECT_EQ(one.latency_min_ns, 10);
  EXPECT_EQ(one.latency_max_ns, 30);
  EXPECT_DOUBLE_EQ(one.latency_mean_ns(), 20.0);
  const StreamStats& two = stats.streams().at(2);
  EXPECT_EQ(two.sequences.lost(), 0U);
  EXPECT_EQ(two.latency_min_ns, 20);
  EXPECT_EQ(stats.received(), 5U);
  EXPECT_EQ(stats.corrupt(), 3U);
  EXPECT_EQ(stats.corrupt(DecodeError::bad_crc), 2U);
  EXPECT_EQ(stats.corrupt(DecodeError::length_mismatch), 1U);
}

}  // namespace
}  // namespace rtmot::messages
