#include "platform/signals.hpp"

#include <pthread.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <system_error>

namespace rtmot::platform {

StopSignals::StopSignals(Hangup hangup) {
  sigemptyset(&watched_);
  sigaddset(&watched_, SIGINT);
  sigaddset(&watched_, SIGTERM);
  if (hangup == Hangup::reloads) sigaddset(&watched_, SIGHUP);
  if (const int error = pthread_sigmask(SIG_BLOCK, &watched_, &previous_mask_); error != 0) {
    throw std::system_error(error, std::generic_category(), "pthread_sigmask");
  }
  // main() blocks SIGHUP from the first instruction on (apps/main.cpp), so that a `run` being
  // started keeps one sent early; a command for which it ends the process gets it back, and a
  // SIGHUP held since then takes its default action now, as it would have at once.
  if (hangup == Hangup::ends) {
    sigset_t hangup_only;
    sigemptyset(&hangup_only);
    sigaddset(&hangup_only, SIGHUP);
    pthread_sigmask(SIG_UNBLOCK, &hangup_only, nullptr);
  }
  watcher_ = std::thread([this] { watch(); });
}

StopSignals::~StopSignals() {
  // Wake the watcher with a signal only it can be waiting for; `closing_` tells it this is us.
  closing_.store(true, std::memory_order_release);
  pthread_kill(watcher_.native_handle(), SIGTERM);
  watcher_.join();
  pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

std::uint64_t StopSignals::reload_requests() const {
  const std::lock_guard<std::mutex> lock(reload_mutex_);
  return reloads_;
}

std::uint64_t StopSignals::wait_for_reload(std::uint64_t seen,
                                           std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(reload_mutex_);
  reload_wake_.wait_for(lock, timeout, [&] { return reloads_ > seen; });
  return reloads_;
}

void StopSignals::watch() {
  pthread_setname_np(pthread_self(), "rtmot-signals");
  while (true) {
    int received = 0;
    if (sigwait(&watched_, &received) != 0) continue;
    if (closing_.load(std::memory_order_acquire)) return;
    if (received == SIGHUP) {
      {
        const std::lock_guard<std::mutex> lock(reload_mutex_);
        ++reloads_;
      }
      reload_wake_.notify_all();
      continue;
    }
    if (stop_requested() && signal_number() != 0) {
      spdlog::warn("{} again: stopping at once", strsignal(received));
      std::_Exit(128 + received);
    }
    spdlog::info("{}: stopping cleanly (send it again to stop at once)", strsignal(received));
    signal_.store(received, std::memory_order_release);
    stop_.store(true, std::memory_order_release);
  }
}

}  // namespace rtmot::platform
