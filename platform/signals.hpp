#pragma once
// Clean stop on SIGINT/SIGTERM, and SIGHUP as "re-read the configuration" for a command that asks
// for it (`rtmot run`, docs/web.md). The signals are blocked and a watcher thread takes them with
// sigwait(), so no async-signal handler runs and no global flag is needed: the flags live in this
// object. The only process-wide state touched is the signal mask, which is how POSIX delivers
// signals at all.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <mutex>
#include <thread>

namespace rtmot::platform {

/// What SIGHUP does to a command.
enum class Hangup {
  /// Its default action (the process ends at once, as before this option existed): commands that
  /// have nothing to re-read.
  ends,
  /// Counted as a request to re-read the configuration (reload_requests(), wait_for_reload()); the
  /// command keeps running. A terminal hanging up no longer ends it either (as under nohup).
  reloads,
};

class StopSignals {
 public:
  /// Construct in main() BEFORE starting any other thread: threads inherit the blocked mask, so no
  /// thread can receive SIGINT/SIGTERM with its default action (which would kill the process
  /// without flushing). A second signal while stopping ends the process at once (exit code 128 +
  /// signal), for a pipeline that does not stop.
  explicit StopSignals(Hangup hangup = Hangup::ends);
  /// Stops the watcher and restores the constructing thread's signal mask (destroy on that thread).
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Polled by the pipeline's loops.
  bool stop_requested() const { return stop_.load(std::memory_order_acquire); }
  const std::atomic<bool>& stop_flag() const { return stop_; }
  /// The signal that asked to stop (SIGINT, SIGTERM), or 0.
  int signal_number() const { return signal_.load(std::memory_order_acquire); }
  /// Ask to stop without a signal (e.g. end of input), same effect for pollers.
  void request_stop() { stop_.store(true, std::memory_order_release); }

  /// SIGHUPs received so far (Hangup::reloads; always 0 otherwise).
  std::uint64_t reload_requests() const;
  /// Waits until reload_requests() is past `seen` or `timeout` has passed; returns the count then.
  /// For a thread that re-reads the configuration (never a pipeline thread).
  std::uint64_t wait_for_reload(std::uint64_t seen, std::chrono::milliseconds timeout) const;

 private:
  void watch();

  sigset_t watched_{};
  sigset_t previous_mask_{};
  std::atomic<bool> stop_{false};
  std::atomic<int> signal_{0};
  std::atomic<bool> closing_{false};
  mutable std::mutex reload_mutex_;
  mutable std::condition_variable reload_wake_;
  std::uint64_t reloads_{0};  // guarded by reload_mutex_
  std::thread watcher_;
};

}  // namespace rtmot::platform
