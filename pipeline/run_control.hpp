#pragma once
// What the stages of one run share besides their hand-offs: the abort flag and the first error.
// A stage that throws records its exception here; the flag makes every wait in the pipeline give
// up, and the registered wakers wake the stages asleep in a hand-off so that they see it.
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "platform/thread.hpp"

namespace rtmot::pipeline {

class RunControl {
 public:
  /// Every wait in the pipeline checks this (relaxed: the wakers order it, see WakeSignal).
  const std::atomic<bool>& aborted() const { return abort_; }

  /// Register before the threads start: called once when the run aborts.
  void on_abort(std::function<void()> wake) { wakers_.push_back(std::move(wake)); }

  /// Records `error` if it is the first, then aborts the run.
  void fail(std::exception_ptr error) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);  // the failure path only, never per frame
      if (!error_) error_ = std::move(error);
    }
    abort_.store(true, std::memory_order_relaxed);
    for (const auto& wake : wakers_) wake();
  }

  /// After every thread was joined: rethrows the first error, if any.
  void rethrow_first_error() const {
    if (error_) std::rethrow_exception(error_);
  }

  /// Runs `body` on a new thread set up by `settings` (name, CPU, priority); an exception from
  /// `body` or `finish` fails the run; `finish` (closing the stage's output) always runs.
  template <typename Body, typename Finish>
  std::thread start(platform::ThreadSettings settings, Body body, Finish finish) {
    return std::thread([this, settings = std::move(settings), body, finish] {
      platform::configure_current_thread(settings);
      try {
        body();
      } catch (...) {
        fail(std::current_exception());
      }
      try {
        finish();
      } catch (...) {
        fail(std::current_exception());
      }
    });
  }

 private:
  std::atomic<bool> abort_{false};
  std::mutex mutex_;
  std::exception_ptr error_;
  std::vector<std::function<void()>> wakers_;  // written before the threads start
};

}  // namespace rtmot::pipeline
