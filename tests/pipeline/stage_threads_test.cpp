// Per-stage thread settings reach the stage threads: a consumer on the sink thread and a detector
// on the detect thread look at their own thread (name, CPU affinity) while the pipeline runs.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <set>

#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"
#include "platform/thread.hpp"

namespace rtmot::pipeline {
namespace {

using namespace test_parts;

struct Seen {
  std::string name;
  std::set<int> cpus;
};

Seen this_thread() {
  Seen seen;
  seen.name = platform::current_thread_name();
  cpu_set_t set;
  CPU_ZERO(&set);
  if (pthread_getaffinity_np(pthread_self(), sizeof(set), &set) == 0) {
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
      if (CPU_ISSET(cpu, &set)) seen.cpus.insert(cpu);
    }
  }
  return seen;
}

class ThreadLookingConsumer : public FrameConsumer {
 public:
  explicit ThreadLookingConsumer(Seen& seen) : seen_(seen) {}
  void consume(const SinkFrame&) override { seen_ = this_thread(); }
  void finish() override {}

 private:
  Seen& seen_;
};

class ThreadLookingDetector : public detector::Detector {
 public:
  explicit ThreadLookingDetector(Seen& seen) : seen_(seen) {}
  void detect(const cv::Mat&, std::int64_t, std::vector<tracker::Detection>& out) override {
    seen_ = this_thread();
    out.clear();
  }
  std::string describe() const override { return "looking"; }

 private:
  Seen& seen_;
};

TEST(StageThreads, PinnedStagesRunOnTheirCpuUnderTheirNames) {
  const Seen main_thread = this_thread();
  ASSERT_FALSE(main_thread.cpus.empty());
  const int last_cpu = *main_thread.cpus.rbegin();  // one this process may use

  Seen sink_seen;
  Seen detect_seen;
  std::vector<PipelineInput> inputs(1);
  inputs[0].source = std::make_unique<PatternSource>(20);
  inputs[0].tracker = sort_for(1000.0);
  std::vector<std::unique_ptr<FrameConsumer>> consumers;
  consumers.push_back(std::make_unique<ThreadLookingConsumer>(sink_seen));
  auto options = quiet(PlaybackMode::realtime);
  options.threads.sink.cpu = last_cpu;
  options.threads.detect.cpu = last_cpu;
  Pipeline pipeline(std::move(inputs), std::make_unique<ThreadLookingDetector>(detect_seen),
                    std::move(consumers), options);
  const std::atomic<bool> stop{false};
  pipeline.run(stop);

  EXPECT_EQ(sink_seen.name, "rtmot-sink");
  EXPECT_EQ(sink_seen.cpus, std::set<int>{last_cpu});
  EXPECT_EQ(detect_seen.name, "rtmot-detect");
  EXPECT_EQ(detect_seen.cpus, std::set<int>{last_cpu});
}

TEST(StageThreads, UnpinnedStagesKeepTheProcessAffinity) {
  const Seen main_thread = this_thread();
  Seen sink_seen;
  Seen detect_seen;
  std::vector<PipelineInput> inputs(1);
  inputs[0].source = std::make_unique<PatternSource>(20);
  inputs[0].tracker = sort_for(1000.0);
  std::vector<std::unique_ptr<FrameConsumer>> consumers;
  consumers.push_back(std::make_unique<ThreadLookingConsumer>(sink_seen));
  Pipeline pipeline(std::move(inputs), std::make_unique<ThreadLookingDetector>(detect_seen),
                    std::move(consumers), quiet(PlaybackMode::realtime));
  const std::atomic<bool> stop{false};
  pipeline.run(stop);
  EXPECT_EQ(sink_seen.cpus, main_thread.cpus);
  EXPECT_EQ(detect_seen.name, "rtmot-detect");
}

}  // namespace
}  // namespace rtmot::pipeline
