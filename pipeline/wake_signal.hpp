#pragma once
// Sleeping until a lock-free hand-off has something for us, without a lock or a system call on the
// fast path: an event count (Vyukov's eventcount; folly::EventCount; the idea behind moodycamel's
// BlockingReaderWriterQueue, whose lightweight semaphore also sleeps only when there is nothing to
// take).
//
// The hand-offs keep their lock-free state (indexes, a fresh bit, a closed flag). A side that finds
// nothing to do calls wait_until(ready): it re-checks `ready` a few times, then registers as a
// waiter and sleeps on a condition variable. The other side, after publishing its change with a
// release store, calls notify(): one fence and one load of the waiter count; only when somebody
// sleeps does it take the mutex and wake them. So when both sides are busy no thread ever touches
// the mutex or the kernel; when a stage waits for the detector (tens of ms) it sleeps in the kernel
// (futex) and costs nothing until woken.
//
// No wake-up is lost: the waiter increments waiters_, then (seq_cst fence) checks `ready`; the
// notifier publishes its change, then (seq_cst fence) reads waiters_. The two fences are ordered
// one way or the other, so either the waiter's check sees the change or the notifier sees the
// waiter. A waiter that saw no change checks again under the mutex before it sleeps, and a notifier
// that saw it takes the same mutex before notifying, so the notification cannot fall between that
// check and the sleep.
//
// Why a mutex and condition variable rather than a raw futex: they are touched only on the slow
// path, which pays a context switch anyway; they are portable C++17 (g++ 9-11 has no atomic wait),
// support a deadline (the batching detector's gather window) and ThreadSanitizer understands them.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace rtmot::pipeline {

class WakeSignal {
 public:
  WakeSignal() = default;
  WakeSignal(const WakeSignal&) = delete;
  WakeSignal& operator=(const WakeSignal&) = delete;

  /// Called after the change that may make a waiter ready was published (release store or
  /// read-modify-write). No lock and no system call unless a thread sleeps here.
  void notify() {
    std::atomic_thread_fence(std::memory_order_seq_cst);
    if (waiters_.load(std::memory_order_relaxed) == 0) return;
    // Taking the mutex orders this notify after a sleeper's last check (it holds the mutex from
    // that check until it sleeps).
    { const std::lock_guard<std::mutex> lock(mutex_); }
    wake_.notify_all();
  }

  /// Returns when `ready()` is true. `ready` must read the hand-off's state with acquire loads and
  /// have no side effects; it is called several times.
  template <typename Ready>
  void wait_until(Ready ready) {
    wait_until_deadline(ready, std::chrono::steady_clock::time_point::max());
  }

  /// Same, but gives up at `deadline`. Returns ready() as last seen.
  template <typename Ready>
  bool wait_until_deadline(Ready ready, std::chrono::steady_clock::time_point deadline) {
    // A short spin catches the other side publishing within microseconds (a full queue drained by a
    // fast stage) without sleeping.
    for (int round = 0; round < spin_rounds; ++round) {
      if (ready()) return true;
    }
    waiters_.fetch_add(1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_seq_cst);
    bool result = ready();
    if (!result) {
      std::unique_lock<std::mutex> lock(mutex_);
      if (deadline == std::chrono::steady_clock::time_point::max()) {
        wake_.wait(lock, [&] { return ready(); });
        result = true;
      } else {
        result = wake_.wait_until(lock, deadline, [&] { return ready(); });
      }
    }
    waiters_.fetch_sub(1, std::memory_order_relaxed);
    return result;
  }

 private:
  static constexpr int spin_rounds = 64;

  std::atomic<int> waiters_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace rtmot::pipeline
