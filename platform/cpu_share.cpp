#include "platform/cpu_share.hpp"

#include <fmt/format.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "platform/clock.hpp"

namespace rtmot::platform {
namespace {

std::int64_t timeval_ns(const timeval& value) {
  return static_cast<std::int64_t>(value.tv_sec) * 1'000'000'000 +
         static_cast<std::int64_t>(value.tv_usec) * 1'000;
}

// The first line of /proc/stat: "cpu user nice system idle iowait irq softirq steal guest
// guest_nice" in clock ticks, for every CPU together. Busy = all but idle and iowait (guest time is
// already inside user and nice).
std::int64_t machine_busy_ns() {
  std::ifstream stat("/proc/stat");
  std::string line;
  if (!std::getline(stat, line) || line.compare(0, 4, "cpu ") != 0) return 0;
  std::istringstream fields(line.substr(4));
  long long value = 0;
  long long busy = 0;
  for (int index = 0; index < 8 && fields >> value; ++index) {
    if (index != 3 && index != 4) busy += value;  // idle, iowait
  }
  const long ticks = ::sysconf(_SC_CLK_TCK);
  return ticks > 0 ? static_cast<std::int64_t>(busy) * (1'000'000'000 / ticks) : 0;
}

int usable_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
  return static_cast<int>(std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN)));
}

}  // namespace

CpuSample sample_cpu() {
  CpuSample sample;
  sample.wall_ns = steady_now_ns();
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) == 0) {
    sample.process_cpu_ns = timeval_ns(usage.ru_utime) + timeval_ns(usage.ru_stime);
  }
  sample.machine_busy_ns = machine_busy_ns();
  return sample;
}

CpuShare cpu_share(const CpuSample& from, const CpuSample& to) {
  CpuShare share;
  share.cpus = usable_cpus();
  share.wall_s = static_cast<double>(to.wall_ns - from.wall_ns) * 1e-9;
  share.process_cpu_s = static_cast<double>(to.process_cpu_ns - from.process_cpu_ns) * 1e-9;
  if (share.wall_s <= 0.0) return share;
  share.cores_used = share.process_cpu_s / share.wall_s;
  if (from.machine_busy_ns > 0 && to.machine_busy_ns >= from.machine_busy_ns) {
    const double busy_s = static_cast<double>(to.machine_busy_ns - from.machine_busy_ns) * 1e-9;
    share.others_cores = std::max(0.0, busy_s / share.wall_s - share.cores_used);
  }
  return share;
}

std::string describe_cpu_share(const CpuShare& share, int threads) {
  std::string text =
      fmt::format("{} thread{} had {:.2f} cores on average ({:.1f} s of CPU in {:.1f} s)", threads,
                  threads == 1 ? "" : "s", share.cores_used, share.process_cpu_s, share.wall_s);
  if (share.others_cores >= 0.0) {
    text += fmt::format("; other processes kept {:.2f} of the {} CPUs busy meanwhile",
                        share.others_cores, share.cpus);
    // Fewer cores than threads, and the machine had none to spare: the threads were waiting for
    // a CPU, not for each other.
    const double wanted = std::min<double>(threads, share.cpus);
    if (share.cores_used < wanted - 0.25 &&
        share.cores_used + share.others_cores > share.cpus - 0.35) {
      text += " (the threads waited for a CPU: the machine was busy)";
    }
  }
  return text;
}

}  // namespace rtmot::platform
