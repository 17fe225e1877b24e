#pragma once
// How many cores a process actually had over a span, and how busy the machine was with others:
// what a parallel command (rtmot study --jobs N) says at its end, so that "N threads used about one
// core" reads with its reason. Its threads were runnable all along (they share nothing but a
// counter); on a shared machine they wait for a CPU that other processes hold, which only the
// machine's own counters show. Linux: /proc/stat for the machine, getrusage for this process.
#include <cstdint>
#include <string>

namespace rtmot::platform {

struct CpuSample {
  std::int64_t wall_ns{0};         // steady clock
  std::int64_t process_cpu_ns{0};  // this process, every thread it ever had: user + system
  std::int64_t machine_busy_ns{
      0};  // every CPU of the machine, not idle (0 if /proc/stat is absent)
};

CpuSample sample_cpu();

struct CpuShare {
  double wall_s{0.0};
  double process_cpu_s{0.0};
  double cores_used{0.0};     // this process's CPU time / wall time
  double others_cores{-1.0};  // the machine's busy CPUs less ours, on average; -1 = unknown
  int cpus{0};                // CPUs this process may run on (affinity)
};

CpuShare cpu_share(const CpuSample& from, const CpuSample& to);

/// One phrase for a final line, e.g. "2 threads had 1.02 cores on average (10.4 s of CPU in
/// 10.2 s); other processes kept 0.96 of the 2 CPUs busy meanwhile". `threads`: how many the
/// command ran.
std::string describe_cpu_share(const CpuShare& share, int threads);

}  // namespace rtmot::platform
