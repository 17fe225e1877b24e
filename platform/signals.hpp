#pragma once
// Clean stop on SIGINT/SIGTERM. The signals are blocked and a watcher thread takes them with
// sigwait(), so no async-signal handler runs and no global flag is needed: the flag lives in this
// object. The only process-wide state touched is the signal mask, which is how POSIX delivers
// signals at all.
#include <atomic>
#include <csignal>
#include <thread>

namespace rtmot::platform {

class StopSignals {
 public:
  /// Construct in main() BEFORE starting any other thread: threads inherit the blocked mask, so no
  /// thread can receive SIGINT/SIGTERM with its default action (which would kill the process
  /// without flushing). A second signal while stopping ends the process at once (exit code 128 +
  /// signal), for a pipeline that does not stop.
  StopSignals();
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

 private:
  void watch();

  sigset_t watched_{};
  sigset_t previous_mask_{};
  std::atomic<bool> stop_{false};
  std::atomic<int> signal_{0};
  std::atomic<bool> closing_{false};
  std::thread watcher_;
};

}  // namespace rtmot::platform
