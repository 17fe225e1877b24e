#pragma once
// Waiting without locks: the stages poll their lock-free hand-offs. A short spin catches the common
// case (the other side is about to publish), yielding keeps a 2-core board usable, and the sleep
// bounds the CPU burnt by an idle stage. The added latency is at most one sleep step (100 us),
// small next to a 50-250 ms detector; a condition variable would put a lock on every hand-off
// instead.
#include <chrono>
#include <thread>

namespace rtmot::pipeline {

class Backoff {
 public:
  void pause() {
    if (rounds_ < spin_rounds) {
      ++rounds_;  // busy-wait: the other side usually publishes within microseconds
    } else if (rounds_ < spin_rounds + yield_rounds) {
      ++rounds_;
      std::this_thread::yield();
    } else {
      std::this_thread::sleep_for(sleep_step);
    }
  }
  void reset() { rounds_ = 0; }

 private:
  static constexpr int spin_rounds = 64;
  static constexpr int yield_rounds = 16;
  static constexpr std::chrono::microseconds sleep_step{100};
  int rounds_{0};
};

}  // namespace rtmot::pipeline
