#pragma once
// What the capture stages of one pipeline know together: how many of its sources are in an outage
// now. Each source logs its own outage (and "still down" every 30 s); with several sources, the
// operator reading a board's journal also gets one line when none of them delivers pictures any
// more, one every 30 s while that lasts, and one when the first comes back, instead of having to
// add up N sources' lines. A single source's own lines already say it: no extra line.
//
// Lock-free: every capture thread calls it from its own loop. down_ is a counter (acq_rel
// read-modify-writes: the thread whose increment completes "every source down" is the one that
// announces it, exactly once per episode). The episode's start is stored before next_line_ns_ is
// released, so a thread that acquires a due next_line_ns_ reads the right start; next_line_ns_ is
// the far future outside an episode, and the thread that wins its compare-exchange prints the
// periodic line, so each is printed once.
#include <atomic>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace rtmot::pipeline {

class OutageBoard {
 public:
  static constexpr std::int64_t kRepeatNs = 30'000'000'000;

  explicit OutageBoard(int sources, std::int64_t repeat_ns = kRepeatNs)
      : sources_(sources), repeat_ns_(repeat_ns) {}

  /// A source's outage began at `now_ns`: the line to log if every source is now down.
  std::optional<std::string> went_down(std::int64_t now_ns);
  /// A source delivers pictures again: the line to log if it ends an all-down episode.
  std::optional<std::string> came_back(std::int64_t now_ns);
  /// Called on every outage tick: the periodic line while every source is down, when it is due.
  std::optional<std::string> tick(std::int64_t now_ns);

  int down() const { return down_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();

  const int sources_;
  const std::int64_t repeat_ns_;
  std::atomic<int> down_{0};
  std::atomic<std::int64_t> all_down_since_ns_{0};
  std::atomic<std::int64_t> next_line_ns_{kNever};
};

}  // namespace rtmot::pipeline
