#include "platform/thread.hpp"

#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>

#include <cstring>

namespace rtmot::platform {
namespace {

constexpr std::size_t max_name_length = 15;  // TASK_COMM_LEN - 1

bool set_name(const std::string& name) {
  const std::string kept = name.substr(0, max_name_length);
  const int error = pthread_setname_np(pthread_self(), kept.c_str());
  if (error != 0) spdlog::warn("thread '{}': cannot set its name: {}", kept, std::strerror(error));
  return error == 0;
}

bool pin_to_cpu(const std::string& name, int cpu) {
  if (cpu < 0 || cpu >= CPU_SETSIZE) {
    spdlog::warn("thread '{}': CPU {} does not exist; left unpinned", name, cpu);
    return false;
  }
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  CPU_SET(cpu, &cpus);
  const int error = pthread_setaffinity_np(pthread_self(), sizeof(cpus), &cpus);
  if (error != 0) {
    spdlog::warn("thread '{}': cannot pin to CPU {}: {}; left unpinned", name, cpu,
                 std::strerror(error));
  }
  return error == 0;
}

bool make_realtime(const std::string& name, int priority) {
  const int lowest = sched_get_priority_min(SCHED_FIFO);
  const int highest = sched_get_priority_max(SCHED_FIFO);
  if (priority < lowest || priority > highest) {
    spdlog::warn("thread '{}': SCHED_FIFO priority {} is outside {}..{}; normal scheduling", name,
                 priority, lowest, highest);
    return false;
  }
  sched_param param{};
  param.sched_priority = priority;
  const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (error != 0) {
    // EPERM without CAP_SYS_NICE or an rtprio limit (see docs: limits.conf / systemd LimitRTPRIO).
    spdlog::warn("thread '{}': cannot use SCHED_FIFO priority {}: {}; normal scheduling", name,
                 priority, std::strerror(error));
  }
  return error == 0;
}

}  // namespace

ThreadSetup configure_current_thread(const ThreadSettings& settings) {
  ThreadSetup setup;
  if (!settings.name.empty()) setup.named = set_name(settings.name);
  if (settings.cpu != -1) setup.pinned = pin_to_cpu(settings.name, settings.cpu);
  if (settings.fifo_priority != 0) {
    setup.realtime = make_realtime(settings.name, settings.fifo_priority);
  }
  // What was applied is said too (a refusal is warned about above): an operator checking a
  // board's threads reads it in the journal.
  if (setup.pinned || setup.realtime) {
    spdlog::info("thread '{}':{}{}", settings.name,
                 setup.pinned ? " pinned to CPU " + std::to_string(settings.cpu) : std::string(),
                 setup.realtime ? " SCHED_FIFO priority " + std::to_string(settings.fifo_priority)
                                : std::string());
  }
  return setup;
}

std::string current_thread_name() {
  char name[max_name_length + 1] = {};
  if (pthread_getname_np(pthread_self(), name, sizeof(name)) != 0) return {};
  return name;
}

}  // namespace rtmot::platform
