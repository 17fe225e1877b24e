// What `rtmot study` says about its cores at the end (platform/cpu_share.hpp): the arithmetic on
// given samples, the explanation only when the machine had no core to spare, and real samples of
// this process burning CPU on two threads.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "platform/cpu_share.hpp"

namespace rtmot::platform {
namespace {

constexpr std::int64_t s = 1'000'000'000;

TEST(CpuShare, CoresOfTheProcessAndOfTheOthers) {
  const CpuSample from{0, 0, 100 * s};
  // 10 s: the process used 10.4 s of CPU, the machine 20 s (both of 2 CPUs all the time).
  const CpuSample to{10 * s, 10'400'000'000, 120 * s};
  const CpuShare share = cpu_share(from, to);
  EXPECT_DOUBLE_EQ(share.wall_s, 10.0);
  EXPECT_NEAR(share.cores_used, 1.04, 1e-9);
  EXPECT_NEAR(share.others_cores, 0.96, 1e-9);
}

TEST(CpuShare, SaysTheThreadsWaitedOnlyWhenTheMachineWasFull) {
  CpuShare busy;
  busy.wall_s = 10.0;
  busy.process_cpu_s = 10.4;
  busy.cores_used = 1.04;
  busy.others_cores = 0.96;
  busy.cpus = 2;
  EXPECT_EQ(describe_cpu_share(busy, 2),
            "2 threads had 1.04 cores on average (10.4 s of CPU in 10.0 s); other processes kept "
            "0.96 of the 2 CPUs busy meanwhile (the threads waited for a CPU: the machine was "
            "busy)");
  CpuShare idle = busy;
  idle.cores_used = 1.96;
  idle.process_cpu_s = 19.6;
  idle.others_cores = 0.02;
  EXPECT_EQ(describe_cpu_share(idle, 2),
            "2 threads had 1.96 cores on average (19.6 s of CPU in 10.0 s); other processes kept "
            "0.02 of the 2 CPUs busy meanwhile");
  // One core used with the other idle: a serial program, not a busy machine: no excuse given.
  CpuShare serial = busy;
  serial.others_cores = 0.0;
  EXPECT_EQ(describe_cpu_share(serial, 2).find("waited"), std::string::npos);
}

TEST(CpuShare, RealSamplesCountEveryThreadOfTheProcess) {
  const CpuSample from = sample_cpu();
  std::atomic<bool> stop{false};
  std::vector<std::thread> spinners;
  for (int t = 0; t < 2; ++t) {
    spinners.emplace_back([&stop] {
      volatile unsigned long sink = 0;
      while (!stop.load(std::memory_order_relaxed)) sink = sink + 1;
    });
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  stop = true;
  for (auto& spinner : spinners) spinner.join();  // exited threads' CPU time still counts
  const CpuShare share = cpu_share(from, sample_cpu());
  EXPECT_GT(share.process_cpu_s, 0.05);
  EXPECT_LE(share.cores_used, share.cpus + 0.1);
  EXPECT_GE(share.others_cores, 0.0) << "/proc/stat's busy time includes ours";
}

}  // namespace
}  // namespace rtmot::platform
