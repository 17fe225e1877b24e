#pragma once
// Setting up a pipeline thread: a name (seen in top -H, gdb, perf), optional CPU pinning and
// optional real-time priority. Pinning and SCHED_FIFO need privileges or a suitable CPU set: a
// failure is logged and the thread runs on unpinned at normal priority, rather than the program
// stopping.
#include <string>

namespace rtmot::platform {

struct ThreadSettings {
  std::string name;      // at most 15 characters are kept (the kernel's limit)
  int cpu{-1};           // pin to this CPU; -1 = let the scheduler choose
  int fifo_priority{0};  // SCHED_FIFO priority 1..99; 0 = normal scheduling
};

/// What configure_current_thread() managed to apply.
struct ThreadSetup {
  bool named{false};
  bool pinned{false};
  bool realtime{false};
};

ThreadSetup configure_current_thread(const ThreadSettings& settings);

/// The current thread's name as the kernel knows it.
std::string current_thread_name();

}  // namespace rtmot::platform
