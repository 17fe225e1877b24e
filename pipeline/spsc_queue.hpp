#pragma once
// Bounded single-producer single-consumer ring with preallocated, reused slots (the design of
// folly's ProducerConsumerQueue and moodycamel's ReaderWriterQueue, reduced to what the stages
// need). Items are never moved in or out: the producer fills a slot in place (claim, fill, publish)
// and the consumer reads it in place (front, use, pop). Items that own vectors or images keep their
// capacity across laps of the ring, so steady state allocates nothing.
//
// Memory orders: each index is written by one side only. A side publishes its progress with a
// release store and observes the other's with an acquire load: the producer's writes into a slot
// happen before the consumer reads it, and the consumer's reads of a slot happen before the
// producer refills it. Each side also caches the other's index so it touches the shared line only
// when the cached value says "full" or "empty".
//
// Waiting: a consumer that finds the queue empty, or a producer that finds it full, sleeps in a
// WakeSignal (pipeline/wake_signal.hpp) that the other side notifies after its release store. While
// neither side sleeps, a hand-off is a few loads and stores plus one fence: no lock, no system
// call.
#include <atomic>
#include <cstddef>
#include <vector>

#include "pipeline/wake_signal.hpp"

namespace rtmot::pipeline {

template <typename T>
class SpscQueue {
 public:
  /// Holds up to `capacity` items, each default-constructed and then passed to `prepare(T&)`:
  /// reserve there what the items need, so they never grow in steady state. (Copying a prototype
  /// would not do: a copied vector does not keep the original's capacity.)
  template <typename Prepare>
  SpscQueue(std::size_t capacity, Prepare prepare) : slots_(capacity + 1) {
    for (T& slot : slots_) prepare(slot);
  }
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  std::size_t capacity() const { return slots_.size() - 1; }

  // ---- producer side (one thread) ----

  /// The next free slot to fill in place, or nullptr when full.
  T* try_claim() {
    const std::size_t next = advance(write_);
    if (next == cached_read_) {
      // acquire: the consumer's reads of the slot we are about to reuse happened before its pop.
      cached_read_ = read_.load(std::memory_order_acquire);
      if (next == cached_read_) return nullptr;
    }
    return &slots_[write_.load(std::memory_order_relaxed)];
  }

  /// Waits (asleep) for a free slot; nullptr if `abort` became true first (see wake_all()).
  T* claim(const std::atomic<bool>& abort) {
    if (T* slot = try_claim()) return slot;
    not_full_.wait_until(
        [&] { return try_claim() != nullptr || abort.load(std::memory_order_relaxed); });
    return try_claim();
  }

  /// Makes the claimed slot visible to the consumer.
  void publish() {
    // release: our writes into the slot happen before the consumer's acquire of write_.
    write_.store(advance(write_), std::memory_order_release);
    not_empty_.notify();
  }

  /// No more items will come. Call after the last publish().
  void close() {
    closed_.store(true, std::memory_order_release);
    not_empty_.notify();
  }

  // ---- consumer side (one thread) ----

  /// The oldest published item, or nullptr when empty.
  T* try_front() {
    const std::size_t read = read_.load(std::memory_order_relaxed);
    if (read == cached_write_) {
      // acquire: pairs with publish(), so the item's contents are visible.
      cached_write_ = write_.load(std::memory_order_acquire);
      if (read == cached_write_) return nullptr;
    }
    return &slots_[read];
  }

  /// Waits (asleep) for an item; nullptr once closed and drained, or when `abort` became true.
  T* front(const std::atomic<bool>& abort) {
    if (T* item = try_front()) return item;
    // acquire on closed_ pairs with close(): every publish before it is visible, so one more look
    // after seeing it suffices.
    not_empty_.wait_until([&] {
      return try_front() != nullptr || closed_.load(std::memory_order_acquire) ||
             abort.load(std::memory_order_relaxed);
    });
    return try_front();  // null when aborted or closed and drained
  }

  /// Releases the front item's slot back to the producer.
  void pop() {
    // release: our reads of the slot happen before the producer's acquire of read_ and its refill.
    read_.store(advance(read_), std::memory_order_release);
    not_full_.notify();
  }

  /// Wakes both sides so that they see an abort flag set since they went to sleep.
  void wake_all() {
    not_empty_.notify();
    not_full_.notify();
  }

 private:
  std::size_t advance(const std::atomic<std::size_t>& index) const {
    const std::size_t next = index.load(std::memory_order_relaxed) + 1;
    return next == slots_.size() ? 0 : next;
  }

  std::vector<T> slots_;  // one more than the capacity: "full" must differ from "empty"
  // Producer's line: its index and its cached copy of the consumer's.
  alignas(64) std::atomic<std::size_t> write_{0};
  std::size_t cached_read_{0};
  // Consumer's line.
  alignas(64) std::atomic<std::size_t> read_{0};
  std::size_t cached_write_{0};
  alignas(64) std::atomic<bool> closed_{false};
  WakeSignal not_empty_;  // the consumer sleeps here
  WakeSignal not_full_;   // the producer sleeps here
};

}  // namespace rtmot::pipeline
