// New lines and zones while running (docs/web.md): the track thread takes each posted
// configuration whole and only ever a newer one; the metrics switch to a new configuration's names
// at its first message, while readers render. Run it under -DRTMOT_SANITIZE=thread too: the
// threads below are the web worker (poster, reader), the track thread and the sink thread.
#include "pipeline/events_mailbox.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>

#include "outputs/event_metrics.hpp"

namespace rtmot::pipeline {
namespace {

events::EventsConfig config_number(std::uint32_t n) {
  events::EventsConfig config;
  const double x = static_cast<double>(n);
  config.lines.push_back({"g" + std::to_string(n), {{x, 0.0}, {x, 10.0 + x}}, n % 2 == 0});
  return config;
}

TEST(EventsMailbox, TheTrackThreadTakesWholeConfigurationsNewestFirstNeverOlder) {
  constexpr std::uint32_t kPosts = 2000;
  EventsMailbox mailbox;
  std::thread poster([&] {
    for (std::uint32_t n = 1; n <= kPosts; ++n) mailbox.post(config_number(n), n);
  });
  std::uint32_t last = 0;
  std::uint32_t taken = 0;
  while (last < kPosts) {  // the track thread, between frames
    const PostedEvents* posted = mailbox.take();
    if (posted == nullptr) continue;
    ASSERT_GT(posted->generation, last);
    const auto& line = posted->config.lines.at(0);
    ASSERT_EQ(line.name, "g" + std::to_string(posted->generation));
    ASSERT_EQ(line.segment.from.x, static_cast<double>(posted->generation));
    ASSERT_EQ(line.segment.to.y, 10.0 + posted->generation);
    last = posted->generation;
    ++taken;
  }
  poster.join();
  EXPECT_EQ(mailbox.take(), nullptr);  // the last one was taken: nothing left
  EXPECT_GE(taken, 1U);
}

TEST(EventsMailbox, MetricsCountEachEventUnderTheNamesOfItsConfiguration) {
  outputs::EventMetrics metrics({{7, {"door"}, {}}});
  messages::FrameResult frame;
  frame.stream_id = 7;
  frame.events.push_back({});
  frame.events[0].kind = events::EventKind::line_in;
  frame.events[0].index = 0;
  metrics.observe(frame);  // configuration 0: door
  ASSERT_TRUE(metrics.post({7, {"hall", "stairs"}, {}}, 1));
  EXPECT_FALSE(metrics.post({8, {"x"}, {}}, 1));  // no such stream
  metrics.observe(frame);  // still configuration 0: the track stage has not taken the new one
  frame.events_generation = 1;
  frame.events[0].index = 1;
  metrics.observe(frame);  // the first message of configuration 1: stairs
  frame.events_generation = 2;
  metrics.observe(frame);  // a configuration never posted: counted nowhere
  const nlohmann::json status = metrics.status().at(0);
  EXPECT_EQ(status["generation"], 1);
  ASSERT_EQ(status["lines"].size(), 2U);
  EXPECT_EQ(status["lines"][0]["name"], "hall");
  EXPECT_EQ(status["lines"][0]["in"], 0);
  EXPECT_EQ(status["lines"][1]["name"], "stairs");
  EXPECT_EQ(status["lines"][1]["in"], 1);
}

// The sink counts and switches while a poster posts and a reader renders (what TSan checks).
TEST(EventsMailbox, MetricsSwitchWhileReadAndPosted) {
  constexpr std::uint32_t kConfigurations = 50;
  outputs::EventMetrics metrics({{1, {"l0"}, {}}});
  std::atomic<std::uint32_t> posted{0};
  std::atomic<bool> done{false};
  std::thread poster([&] {
    for (std::uint32_t n = 1; n <= kConfigurations; ++n) {
      metrics.post({1, {"l" + std::to_string(n)}, {}}, n);
      posted.store(n, std::memory_order_release);
    }
  });
  std::thread reader([&] {
    while (!done.load()) {
      const std::string text = [&] {
        std::string out;
        metrics.render(out);
        return out;
      }();
      ASSERT_NE(text.find("rtmot_line_crossings_total{stream=\"1\",line=\"l"), std::string::npos);
    }
  });
  messages::FrameResult frame;  // the sink thread
  frame.stream_id = 1;
  frame.events.push_back({});
  frame.events[0].kind = events::EventKind::line_out;
  std::uint32_t generation = 0;
  while (generation < kConfigurations) {
    const std::uint32_t newest = posted.load(std::memory_order_acquire);
    if (newest > generation) generation = newest;
    frame.events_generation = generation;
    metrics.observe(frame);
  }
  done.store(true);
  poster.join();
  reader.join();
  const nlohmann::json status = metrics.status().at(0);
  EXPECT_EQ(status["generation"], kConfigurations);
  EXPECT_EQ(status["lines"][0]["name"], "l" + std::to_string(kConfigurations));
  EXPECT_EQ(status["lines"][0]["out"], 1);
}

}  // namespace
}  // namespace rtmot::pipeline
