// The two lock-free hand-offs: what each promises alone, then a stress test with random delays that
// checks no frame is delivered twice, out of order or torn (run it under ThreadSanitizer too).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <random>
#include <thread>
#include <vector>

#include "pipeline/latest_frame_slot.hpp"
#include "pipeline/spsc_queue.hpp"

namespace rtmot::pipeline {
namespace {

const std::atomic<bool> never{false};

// A value per (sequence, position) so that a buffer mixing two frames is detected.
std::int32_t pattern(std::int64_t sequence, int position) {
  return static_cast<std::int32_t>((sequence * 2654435761LL) ^ (position * 40503LL));
}

void fill(cv::Mat& image, std::int64_t sequence) {
  auto* data = image.ptr<std::int32_t>();
  const int n = static_cast<int>(image.total());
  for (int i = 0; i < n; ++i) data[i] = pattern(sequence, i);
}

bool intact(const cv::Mat& image, std::int64_t sequence) {
  const auto* data = image.ptr<std::int32_t>();
  const int n = static_cast<int>(image.total());
  for (int i = 0; i < n; ++i) {
    if (data[i] != pattern(sequence, i)) return false;
  }
  return true;
}

void publish_frame(LatestFrameSlot& slot, std::int64_t sequence) {
  FrameSlotItem& back = slot.back();
  back.image.create(32, 32, CV_32SC1);
  fill(back.image, sequence);
  back.info.frame_number = sequence;
  ASSERT_TRUE(slot.publish(never));
}

TEST(LatestFrameSlot, ConsumerGetsTheNewestFrameAndOverwrittenOnesCountAsDropped) {
  LatestFrameSlot slot(SlotMode::latest);
  EXPECT_FALSE(slot.try_take());
  publish_frame(slot, 1);
  publish_frame(slot, 2);
  publish_frame(slot, 3);
  ASSERT_TRUE(slot.try_take());
  EXPECT_EQ(slot.front().info.frame_number, 3);
  EXPECT_TRUE(intact(slot.front().image, 3));
  EXPECT_EQ(slot.overwritten(), 2);
  EXPECT_FALSE(slot.try_take()) << "a frame must be delivered once";
  publish_frame(slot, 4);
  ASSERT_TRUE(slot.try_take());
  EXPECT_EQ(slot.front().info.frame_number, 4);
  EXPECT_EQ(slot.overwritten(), 2);
}

TEST(LatestFrameSlot, BuffersAreReusedWithoutReallocation) {
  LatestFrameSlot slot(SlotMode::latest);
  std::vector<const void*> seen;
  for (int i = 1; i <= 30; ++i) {
    publish_frame(slot, i);
    if (i % 3 != 0) {
      ASSERT_TRUE(slot.try_take());
      seen.push_back(slot.front().image.data);
    }
  }
  // Only three buffers exist, each allocated once: the frames' pixels live in at most three places.
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  EXPECT_LE(seen.size(), 3U);
}

TEST(LatestFrameSlot, TakeReturnsTheLastFrameAfterCloseThenFalse) {
  LatestFrameSlot slot(SlotMode::latest);
  publish_frame(slot, 7);
  slot.close();
  ASSERT_TRUE(slot.take(never));
  EXPECT_EQ(slot.front().info.frame_number, 7);
  EXPECT_FALSE(slot.take(never));
}

TEST(LatestFrameSlot, EveryFrameModeProducerWaitsUntilTakenAndAbortEndsTheWait) {
  LatestFrameSlot slot(SlotMode::every_frame);
  publish_frame(slot, 1);
  std::atomic<bool> abort{true};
  slot.back().info.frame_number = 2;
  EXPECT_FALSE(slot.publish(abort)) << "frame 1 not taken yet: must not overwrite it";
  ASSERT_TRUE(slot.try_take());
  EXPECT_EQ(slot.front().info.frame_number, 1);
  EXPECT_TRUE(slot.publish(abort));
  EXPECT_EQ(slot.overwritten(), 0);
}

struct Item {
  std::int64_t sequence{0};
  std::vector<std::int32_t> payload;
};

TEST(SpscQueue, FifoBoundedAndSlotsKeepTheirCapacity) {
  SpscQueue<Item> queue(3, [](Item& item) { item.payload.reserve(64); });
  EXPECT_EQ(queue.capacity(), 3U);
  EXPECT_EQ(queue.try_front(), nullptr);
  for (int i = 0; i < 3; ++i) {
    Item* slot = queue.try_claim();
    ASSERT_NE(slot, nullptr);
    EXPECT_GE(slot->payload.capacity(), 64U) << "prepared before first use";
    slot->sequence = i;
    slot->payload.assign(10, i);
    queue.publish();
  }
  EXPECT_EQ(queue.try_claim(), nullptr) << "full at capacity";
  for (int i = 0; i < 3; ++i) {
    Item* front = queue.try_front();
    ASSERT_NE(front, nullptr);
    EXPECT_EQ(front->sequence, i);
    queue.pop();
  }
  EXPECT_EQ(queue.try_front(), nullptr);
  queue.close();
  EXPECT_EQ(queue.front(never), nullptr);
  // Refilling reuses the slots' vectors in place: same storage, no new allocation.
  for (int i = 0; i < 3; ++i) {
    Item* again = queue.try_claim();
    ASSERT_NE(again, nullptr);
    const void* before = again->payload.data();
    again->payload.assign(64, -i);
    EXPECT_EQ(again->payload.data(), before);
    queue.publish();
  }
}

void random_pause(std::mt19937& random) {
  const int kind = std::uniform_int_distribution<int>(0, 99)(random);
  if (kind < 3) {
    std::this_thread::sleep_for(std::chrono::microseconds(kind * 50));
  } else if (kind < 10) {
    std::this_thread::yield();
  }
}

// capture -> slot -> detect -> queue -> track, as in the pipeline, with random delays everywhere.
void stress(SlotMode mode, std::int64_t frames, std::uint32_t seed) {
  LatestFrameSlot slot(mode);
  SpscQueue<Item> queue(4, [](Item& item) { item.payload.reserve(256); });

  std::thread producer([&] {
    std::mt19937 random(seed);
    for (std::int64_t sequence = 1; sequence <= frames; ++sequence) {
      FrameSlotItem& back = slot.back();
      back.image.create(16, 16, CV_32SC1);
      fill(back.image, sequence);
      back.info.frame_number = sequence;
      slot.publish(never);
      random_pause(random);
    }
    slot.close();
  });

  std::int64_t taken = 0;
  std::int64_t torn_in_slot = 0;
  std::thread middle([&] {
    std::mt19937 random(seed + 1);
    while (slot.take(never)) {
      const FrameSlotItem& frame = slot.front();
      if (!intact(frame.image, frame.info.frame_number)) ++torn_in_slot;
      ++taken;
      Item* out = queue.claim(never);
      out->sequence = frame.info.frame_number;
      const auto* data = frame.image.ptr<std::int32_t>();
      out->payload.assign(data, data + frame.image.total());
      random_pause(random);
      queue.publish();
    }
    queue.close();
  });

  std::vector<std::int64_t> delivered;
  delivered.reserve(static_cast<std::size_t>(frames));
  std::int64_t torn_in_queue = 0;
  std::mt19937 random(seed + 2);
  while (Item* item = queue.front(never)) {
    delivered.push_back(item->sequence);
    for (std::size_t i = 0; i < item->payload.size(); ++i) {
      if (item->payload[i] != pattern(item->sequence, static_cast<int>(i))) {
        ++torn_in_queue;
        break;
      }
    }
    random_pause(random);
    queue.pop();
  }
  producer.join();
  middle.join();

  EXPECT_EQ(torn_in_slot, 0);
  EXPECT_EQ(torn_in_queue, 0);
  ASSERT_FALSE(delivered.empty());
  for (std::size_t i = 1; i < delivered.size(); ++i) {
    ASSERT_LT(delivered[i - 1], delivered[i]) << "duplicate or out of order at " << i;
  }
  EXPECT_EQ(delivered.back(), frames) << "the last frame must survive the shutdown";
  EXPECT_EQ(static_cast<std::int64_t>(delivered.size()), taken);
  EXPECT_EQ(taken + slot.overwritten(), frames) << "every frame is either taken or dropped";
  if (mode == SlotMode::every_frame) {
    EXPECT_EQ(taken, frames);
  }
}

// A consumer asleep in take()/front() must wake for the last item and then for close(), and a
// sleeping side must wake when another thread sets the abort flag and wakes the hand-off. The
// sleeper is started first and given time to fall asleep; if a wake-up were lost the join below
// would hang and the test time out (ctest's limit), so every assertion here can fail.
template <typename Sleep>
void expect_wakes(Sleep sleeper, const std::function<void()>& waker) {
  std::atomic<bool> returned{false};
  std::thread thread([&] {
    sleeper();
    returned.store(true);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // long enough to be asleep
  EXPECT_FALSE(returned.load()) << "must wait while nothing is there";
  waker();
  thread.join();
  EXPECT_TRUE(returned.load());
}

TEST(BlockingHandoff, SleepingSlotConsumerWakesForTheLastFrameAndForClose) {
  for (const SlotMode mode : {SlotMode::latest, SlotMode::every_frame}) {
    LatestFrameSlot slot(mode);
    bool took = false;
    expect_wakes([&] { took = slot.take(never); }, [&] { publish_frame(slot, 1); });
    EXPECT_TRUE(took);
    EXPECT_EQ(slot.front().info.frame_number, 1);
    expect_wakes([&] { took = slot.take(never); }, [&] { slot.close(); });
    EXPECT_FALSE(took) << "closed and drained";
  }
}

TEST(BlockingHandoff, SleepingQueueConsumerWakesForTheLastItemAndForClose) {
  SpscQueue<Item> queue(2, [](Item&) {});
  Item* got = nullptr;
  expect_wakes([&] { got = queue.front(never); },
               [&] {
                 queue.try_claim()->sequence = 42;
                 queue.publish();
               });
  ASSERT_NE(got, nullptr);
  EXPECT_EQ(got->sequence, 42);
  queue.pop();
  expect_wakes([&] { got = queue.front(never); }, [&] { queue.close(); });
  EXPECT_EQ(got, nullptr);
}

TEST(BlockingHandoff, SleepingProducersWakeWhenRoomIsMadeOrOnAbort) {
  SpscQueue<Item> queue(1, [](Item&) {});
  queue.try_claim();
  queue.publish();  // full
  Item* claimed = nullptr;
  expect_wakes([&] { claimed = queue.claim(never); }, [&] { queue.pop(); });
  EXPECT_NE(claimed, nullptr);
  queue.publish();  // full again
  std::atomic<bool> abort{false};
  expect_wakes([&] { claimed = queue.claim(abort); },
               [&] {
                 abort.store(true);
                 queue.wake_all();
               });
  EXPECT_EQ(claimed, nullptr);

  LatestFrameSlot slot(SlotMode::every_frame);
  publish_frame(slot, 1);
  bool published = false;
  std::atomic<bool> slot_abort{false};
  expect_wakes([&] { published = slot.publish(slot_abort); },
               [&] {
                 slot_abort.store(true);
                 slot.wake_all();
               });
  EXPECT_FALSE(published) << "frame 1 was never taken";
}

TEST(BlockingHandoff, OneSignalServesAConsumerOfSeveralSlots) {
  WakeSignal any;
  LatestFrameSlot first(SlotMode::latest, &any);
  LatestFrameSlot second(SlotMode::latest, &any);
  expect_wakes([&] { any.wait_until([&] { return first.fresh() || second.fresh(); }); },
               [&] { publish_frame(second, 5); });
  EXPECT_FALSE(first.try_take());
  ASSERT_TRUE(second.try_take());
  EXPECT_EQ(second.front().info.frame_number, 5);
}

TEST(HandoffStress, LatestModeNeverTearsDuplicatesOrReorders) {
  stress(SlotMode::latest, 20000, 11);
}

TEST(HandoffStress, EveryFrameModeDeliversEveryFrameInOrder) {
  stress(SlotMode::every_frame, 5000, 23);
}

}  // namespace
}  // namespace rtmot::pipeline
