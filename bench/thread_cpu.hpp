#pragma once
// CPU time of this process's threads by name, from /proc/self/task/*/stat (utime + stime, in clock
// ticks), for benchmarks that must show what the pipeline's waiting threads cost. A sampler thread
// reads every task periodically and keeps each thread's last reading, because the pipeline's
// threads are gone (and their /proc entries with them) by the time run() returns. Resolution: one
// clock tick (10 ms at USER_HZ 100) per thread plus what a thread burns after the last sample.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

namespace rtmot::bench {

class ThreadCpuSampler {
 public:
  explicit ThreadCpuSampler(std::chrono::milliseconds period = std::chrono::milliseconds(50))
      : period_(period), thread_([this] { loop(); }) {}
  ~ThreadCpuSampler() { stop(); }
  ThreadCpuSampler(const ThreadCpuSampler&) = delete;
  ThreadCpuSampler& operator=(const ThreadCpuSampler&) = delete;

  /// Takes a last sample and ends the sampler. Idempotent.
  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (stopped_) return;
      stopped_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }

  /// CPU seconds used by every thread that carried `name`, summed over threads (after stop()).
  double cpu_seconds(const std::string& name) const {
    double ticks = 0.0;
    for (const auto& [tid, sample] : samples_) {
      if (sample.name == name) ticks += static_cast<double>(sample.ticks);
    }
    return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
  }

 private:
  struct Sample {
    std::string name;
    long long ticks{0};
  };

  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      sample_all();
      if (stopped_) return;
      wake_.wait_for(lock, period_, [this] { return stopped_; });
    }
  }

  void sample_all() {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task", error)) {
      std::ifstream file(entry.path() / "stat");
      std::string line;
      if (!std::getline(file, line)) continue;  // the thread ended meanwhile
      const auto open = line.find('(');
      const auto close = line.rfind(')');
      if (open == std::string::npos || close == std::string::npos) continue;
      // After "pid (comm)": state is field 3, utime field 14, stime field 15 (proc(5)).
      std::istringstream rest(line.substr(close + 2));
      std::string field;
      long long utime = 0;
      long long stime = 0;
      for (int number = 3; number <= 15 && rest >> field; ++number) {
        if (number == 14) utime = std::stoll(field);
        if (number == 15) stime = std::stoll(field);
      }
      Sample& sample = samples_[entry.path().filename().string()];
      sample.name = line.substr(open + 1, close - open - 1);
      sample.ticks = utime + stime;
    }
  }

  const std::chrono::milliseconds period_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopped_{false};
  std::map<std::string, Sample> samples_;  // by tid; written by the sampler, read after stop()
  std::thread thread_;
};

}  // namespace rtmot::bench
