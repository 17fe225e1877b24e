#include <gtest/gtest.h>
#include <sched.h>

#include <thread>

#include "platform/thread.hpp"

namespace rtmot::platform {
namespace {

// Each case runs in its own thread so the test runner's main thread keeps its name and affinity.
template <typename Body>
void in_new_thread(Body body) {
  std::thread(body).join();
}

TEST(Thread, NamesTheCurrentThreadCuttingAt15Characters) {
  in_new_thread([] {
    const ThreadSetup setup = configure_current_thread({"rtmot-capture-stage", -1, 0});
    EXPECT_TRUE(setup.named);
    EXPECT_FALSE(setup.pinned);
    EXPECT_FALSE(setup.realtime);
    EXPECT_EQ(current_thread_name(), "rtmot-capture-s");
  });
}

TEST(Thread, PinsToACpuWeMayUse) {
  cpu_set_t allowed;
  ASSERT_EQ(sched_getaffinity(0, sizeof(allowed), &allowed), 0);
  int cpu = 0;
  while (!CPU_ISSET(cpu, &allowed)) ++cpu;
  in_new_thread([cpu] {
    const ThreadSetup setup = configure_current_thread({"pinned", cpu, 0});
    EXPECT_TRUE(setup.pinned);
    EXPECT_EQ(sched_getcpu(), cpu);
    cpu_set_t now;
    ASSERT_EQ(sched_getaffinity(0, sizeof(now), &now), 0);
    EXPECT_EQ(CPU_COUNT(&now), 1);
  });
}

TEST(Thread, ImpossibleRequestsFailGracefully) {
  in_new_thread([] {
    const ThreadSetup setup = configure_current_thread({"graceful", CPU_SETSIZE + 5, 1000});
    EXPECT_TRUE(setup.named);
    EXPECT_FALSE(setup.pinned);
    EXPECT_FALSE(setup.realtime);
    EXPECT_EQ(sched_getscheduler(0), SCHED_OTHER);
  });
}

TEST(Thread, RealtimeIsAppliedOrReportedAsNot) {
  in_new_thread([] {
    const ThreadSetup setup = configure_current_thread({"fifo", -1, 10});
    // Whether SCHED_FIFO is allowed depends on privileges; what is reported must be the truth.
    EXPECT_EQ(setup.realtime, sched_getscheduler(0) == SCHED_FIFO);
  });
}

}  // namespace
}  // namespace rtmot::platform
