#pragma once
// Lock-free "latest item" hand-off between one producer and one consumer thread: a triple buffer.
// The producer fills its back buffer and swaps it with the middle one; the consumer swaps its front
// buffer with the middle one when the middle is fresh. Neither side ever touches the other's
// buffer, so an item is never torn, and in `latest` mode the producer never waits: an item
// overwritten in the middle before the consumer took it is dropped. `every_frame` mode (offline
// replay only) makes the producer wait until the previous item was taken.
//
// The three buffers are allocated once and reused in place (an image keeps its pixels as long as
// the frame size is unchanged), so steady state allocates nothing. A side that must wait sleeps in
// a WakeSignal (pipeline/wake_signal.hpp); neither side takes a lock or makes a system call while
// the other does not sleep.
#include <array>
#include <atomic>
#include <cstdint>

#include "pipeline/wake_signal.hpp"

namespace rtmot::pipeline {

enum class SlotMode { latest, every_frame };

template <typename T>
class LatestSlot {
 public:
  /// `consumer_signal`: where the consumer sleeps; give several slots the same one when a single
  /// consumer waits for any of them (the batching detector). Null: the slot's own.
  explicit LatestSlot(SlotMode mode, WakeSignal* consumer_signal = nullptr)
      : mode_(mode), consumer_(consumer_signal != nullptr ? consumer_signal : &own_signal_) {}
  LatestSlot(const LatestSlot&) = delete;
  LatestSlot& operator=(const LatestSlot&) = delete;

  // ---- producer side (one thread) ----

  /// The buffer the producer fills next. Only the producer touches it until publish().
  T& back() { return buffers_[back_]; }

  /// every_frame mode: waits (asleep) until the consumer took the previous item, so that publish()
  /// will not overwrite it. False if `abort` became true first (see wake_all()). Returns at once in
  /// latest mode.
  bool wait_for_room(const std::atomic<bool>& abort) {
    if (mode_ != SlotMode::every_frame) return true;
    // acquire: pairs with the consumer's acq_rel exchange that cleared the fresh bit, so that its
    // reads of the buffer it gave back happen before we write into that buffer later.
    room_.wait_until([&] {
      return (middle_.load(std::memory_order_acquire) & fresh_bit) == 0 ||
             abort.load(std::memory_order_relaxed);
    });
    return (middle_.load(std::memory_order_acquire) & fresh_bit) == 0;
  }

  /// Hands the back buffer to the consumer (in every_frame mode after wait_for_room()). Returns
  /// false, publishing nothing, only if that wait was aborted.
  bool publish(const std::atomic<bool>& abort) {
    if (!wait_for_room(abort)) return false;
    // acq_rel: release publishes our writes to the back buffer to the consumer who will acquire
    // this middle; acquire makes the consumer's last reads of the buffer we get back (it may have
    // just returned it as its old front) happen before our next writes into it.
    const std::uint8_t previous =
        middle_.exchange(static_cast<std::uint8_t>(back_ | fresh_bit), std::memory_order_acq_rel);
    if ((previous & fresh_bit) != 0) {
      // Only the producer writes this counter; relaxed is enough for a statistic.
      overwritten_.store(overwritten_.load(std::memory_order_relaxed) + 1,
                         std::memory_order_relaxed);
    }
    back_ = previous & index_mask;
    consumer_->notify();
    return true;
  }

  /// No more items will come (end of stream or stop). Call after the last publish().
  void close() {
    // release: everything published before is visible to a consumer that acquires `closed_`.
    closed_.store(true, std::memory_order_release);
    consumer_->notify();
  }

  // ---- consumer side (one thread) ----

  /// True if an item was published since the last take (acquire: try_take() will get it).
  bool fresh() const { return (middle_.load(std::memory_order_acquire) & fresh_bit) != 0; }

  /// True once close() was called (acquire: pairs with close(), so every publish before it is
  /// visible and one more try_take() cannot miss a last item).
  bool closed() const { return closed_.load(std::memory_order_acquire); }

  /// Takes the newest item if one was published since the last take. On true, front() is it.
  bool try_take() {
    // relaxed pre-check: avoids a read-modify-write (and cache-line ping-pong) while nothing is
    // new.
    if ((middle_.load(std::memory_order_relaxed) & fresh_bit) == 0) return false;
    // acq_rel: acquire sees the producer's writes to the buffer it published; release hands our
    // finished reads of the old front back before the producer may overwrite it.
    const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = previous & index_mask;
    if (mode_ == SlotMode::every_frame) room_.notify();  // only that producer ever waits
    return true;
  }

  /// Waits (asleep) for the next item. Returns false once the slot is closed and drained or
  /// `abort` is set.
  bool take(const std::atomic<bool>& abort) {
    if (try_take()) return true;
    consumer_->wait_until(
        [&] { return fresh() || closed() || abort.load(std::memory_order_relaxed); });
    if (try_take()) return true;
    return false;  // closed and drained, or aborted
  }

  /// The item last taken. Only the consumer touches it until the next take.
  T& front() { return buffers_[front_]; }

  /// Wakes both sides so that they see an abort flag set since they went to sleep.
  void wake_all() {
    consumer_->notify();
    room_.notify();
  }

  /// Items the producer overwrote before the consumer took them (read any time; approximate while
  /// running, exact after the producer finished).
  std::int64_t overwritten() const { return overwritten_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::uint8_t index_mask = 0x3;
  static constexpr std::uint8_t fresh_bit = 0x4;

  const SlotMode mode_;
  std::array<T, 3> buffers_;
  // Each side's own index lives on its own cache line; `middle_` is the only shared word.
  alignas(64) std::uint8_t back_{0};
  alignas(64) std::uint8_t front_{1};
  alignas(64) std::atomic<std::uint8_t> middle_{2};
  alignas(64) std::atomic<std::int64_t> overwritten_{0};
  std::atomic<bool> closed_{false};
  WakeSignal room_;        // the every_frame producer sleeps here
  WakeSignal own_signal_;  // the consumer sleeps here unless given another
  WakeSignal* const consumer_;
};

}  // namespace rtmot::pipeline
