#include "platform/signals.hpp"

#include <pthread.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <system_error>

namespace rtmot::platform {

StopSignals::StopSignals() {
  sigemptyset(&watched_);
  sigaddset(&watched_, SIGINT);
  sigaddset(&watched_, SIGTERM);
  if (const int error = pthread_sigmask(SIG_BLOCK, &watched_, &previous_mask_); error != 0) {
    throw std::system_error(error, std::generic_category(), "pthread_sigmask");
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

void StopSignals::watch() {
  pthread_setname_np(pthread_self(), "rtmot-signals");
  while (true) {
    int received = 0;
    if (sigwait(&watched_, &received) != 0) continue;
    if (closing_.load(std::memory_order_acquire)) return;
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
