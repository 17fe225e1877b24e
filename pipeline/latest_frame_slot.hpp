#pragma once
// Lock-free "latest frame" hand-off between the capture thread (one producer) and the detector
// thread (one consumer): a triple buffer. The producer fills its back buffer and swaps it with the
// middle one; the consumer swaps its front buffer with the middle one when the middle is fresh.
// Neither side ever touches the other's buffer, so a frame is never torn, and in `latest` mode the
// producer never waits: a frame overwritten in the middle before the consumer took it is dropped.
// `every_frame` mode (offline replay only) makes the producer wait until the previous frame was
// taken.
//
// The three buffers are allocated once; a cv::Mat is reused by the source as long as the frame size
// is unchanged, so steady state allocates nothing.
#include <array>
#include <atomic>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "pipeline/backoff.hpp"
#include "platform/video_source.hpp"

namespace rtmot::pipeline {

struct FrameSlotItem {
  cv::Mat image;
  platform::FrameInfo info;
  bool outage{false};  // no picture: a tick while the live source is reopened (see pipeline.cpp)
};

enum class SlotMode { latest, every_frame };

class LatestFrameSlot {
 public:
  explicit LatestFrameSlot(SlotMode mode) : mode_(mode) {}
  LatestFrameSlot(const LatestFrameSlot&) = delete;
  LatestFrameSlot& operator=(const LatestFrameSlot&) = delete;

  // ---- producer side (one thread) ----

  /// The buffer the producer fills next. Only the producer touches it until publish().
  FrameSlotItem& back() { return buffers_[back_]; }

  /// every_frame mode: waits until the consumer took the previous frame, so that publish() will not
  /// overwrite it. False if `abort` became true first. Returns at once in latest mode.
  bool wait_for_room(const std::atomic<bool>& abort) {
    if (mode_ != SlotMode::every_frame) return true;
    Backoff backoff;
    // acquire: pairs with the consumer's acq_rel exchange that cleared the fresh bit, so that its
    // reads of the buffer it gave back happen before we write into that buffer later.
    while ((middle_.load(std::memory_order_acquire) & fresh_bit) != 0) {
      if (abort.load(std::memory_order_relaxed)) return false;
      backoff.pause();
    }
    return true;
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
    return true;
  }

  /// No more frames will come (end of stream or stop). Call after the last publish().
  void close() {
    // release: everything published before is visible to a consumer that acquires `closed_`.
    closed_.store(true, std::memory_order_release);
  }

  // ---- consumer side (one thread) ----

  /// Takes the newest frame if one was published since the last take. On true, front() is it.
  bool try_take() {
    // relaxed pre-check: avoids a read-modify-write (and cache-line ping-pong) while nothing is
    // new.
    if ((middle_.load(std::memory_order_relaxed) & fresh_bit) == 0) return false;
    // acq_rel: acquire sees the producer's writes to the buffer it published; release hands our
    // finished reads of the old front back before the producer may overwrite it.
    const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = previous & index_mask;
    return true;
  }

  /// Waits for the next frame. Returns false once the slot is closed and drained or `abort` is set.
  bool take(const std::atomic<bool>& abort) {
    Backoff backoff;
    while (!try_take()) {
      if (abort.load(std::memory_order_relaxed)) return false;
      // acquire pairs with close(): seeing closed means every publish is visible, so one more
      // try_take() cannot miss a last frame.
      if (closed_.load(std::memory_order_acquire)) return try_take();
      backoff.pause();
    }
    return true;
  }

  /// The frame last taken. Only the consumer touches it until the next take.
  FrameSlotItem& front() { return buffers_[front_]; }

  /// Frames the producer overwrote before the consumer took them (read any time; approximate while
  /// running, exact after the producer finished).
  std::int64_t overwritten() const { return overwritten_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::uint8_t index_mask = 0x3;
  static constexpr std::uint8_t fresh_bit = 0x4;

  const SlotMode mode_;
  std::array<FrameSlotItem, 3> buffers_;
  // Each side's own index lives on its own cache line; `middle_` is the only shared word.
  alignas(64) std::uint8_t back_{0};
  alignas(64) std::uint8_t front_{1};
  alignas(64) std::atomic<std::uint8_t> middle_{2};
  alignas(64) std::atomic<std::int64_t> overwritten_{0};
  std::atomic<bool> closed_{false};
};

}  // namespace rtmot::pipeline
