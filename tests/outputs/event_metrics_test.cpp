// The events' Prometheus series against the events themselves: the rtmot tracker on PETS09-S2L1's
// detections, two lines and a zone counted, every frame's events sent through the metrics and
// through a JSON line read back; the series, the JSON events and the counter's own totals agree.
#include "outputs/event_metrics.hpp"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <string>

#include "common/utf8.hpp"
#include "events/event_counter.hpp"
#include "messages/json_line_decoder.hpp"
#include "messages/jsonl_sink.hpp"
#include "metrics_scrape.hpp"
#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"
#include "outputs/pipeline_metrics.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::outputs {
namespace {

using test::value_of;

// PETS09-S2L1's public detections and the rtmot tracker set for the sequence's frame size and rate.
struct S2L1Tracking {
  static std::filesystem::path dir() { return test::shared_path("data/mot15-train/PETS09-S2L1"); }
  static tracker::TrackerConfig config_for(const motio::SequenceInfo& sequence) {
    auto config = *tracker::find_preset("rtmot");
    config.frame_rate = sequence.frame_rate;
    config.image_width = static_cast<float>(sequence.width);
    config.image_height = static_cast<float>(sequence.height);
    return config;
  }
  motio::SequenceInfo info = motio::read_seqinfo(dir() / "seqinfo.ini");
  motio::FrameDetections detections{
      motio::read_mot_file(dir() / "det" / "det.txt", motio::MotFileKind::detections)};
  tracker::Tracker tracker{config_for(info)};
};

TEST(EventMetrics, SeriesEqualTheEventsSentAndTheCountersTotals) {
  RTMOT_REQUIRE_FILE(S2L1Tracking::dir() / "det" / "det.txt");
  S2L1Tracking s2l1;
  const auto& info = s2l1.info;
  const auto& detections = s2l1.detections;
  auto& tracker = s2l1.tracker;

  events::EventsConfig config;
  config.lines.push_back({"middle \"m\"", {{384.0, 0.0}, {384.0, 576.0}}, true});
  config.lines.push_back({"low", {{0.0, 432.0}, {768.0, 432.0}}, true});
  config.zones.push_back({"left", {{38, 172}, {346, 172}, {346, 547}, {38, 547}}, 5.0});
  events::EventCounter counter(config);

  EventMetrics event_metrics({{3, {"middle \"m\"", "low"}, {"left"}}});
  PipelineMetrics metrics({}, {3});
  metrics.set_event_metrics(&event_metrics);
  EventMetricsSink sink(event_metrics);
  std::map<std::string, int> from_json;  // "kind index" -> count
  fmt::memory_buffer line;
  messages::DecodedMessage decoded;
  messages::FrameResult frame;
  frame.stream_id = 3;
  for (int f = 1; f <= info.length; ++f) {
    const double time = (f - 1) / info.frame_rate;
    const auto& reports = tracker.update(detections.at(f), time);
    frame.frame_number = f;
    frame.sequence = static_cast<std::uint64_t>(f - 1);
    frame.pts_ns = static_cast<std::int64_t>(time * 1e9);
    frame.tracks.assign(reports.begin(), reports.end());
    const auto& decided = counter.update(reports, time);
    frame.events.assign(decided.begin(), decided.end());
    sink.write(frame);
    line.clear();
    messages::append_json_line(frame, static_cast<std::uint32_t>(frame.tracks.size()), false,
                               messages::JsonLineExtras{1, nullptr}, line);
    std::string problem;
    ASSERT_TRUE(messages::decode_json_line(reinterpret_cast<const std::uint8_t*>(line.data()),
                                           line.size(), decoded, problem))
        << problem;
    for (const auto& event : decoded.frame.events)
      ++from_json[std::string(events::kEventKindNames.name(event.kind)) + " " +
                  std::to_string(event.index)];
  }
  const std::string text = metrics.render();
  const auto line_series = [&](const char* name, const char* direction) {
    return value_of(text, std::string("rtmot_line_crossings_total{stream=\"3\",line=\"") + name +
                              "\",direction=\"" + direction + "\"}");
  };
  EXPECT_EQ(line_series(R"(middle \"m\")", "in"), from_json["line_in 0"]);
  EXPECT_EQ(line_series(R"(middle \"m\")", "out"), from_json["line_out 0"]);
  EXPECT_EQ(line_series("low", "in"), from_json["line_in 1"]);
  EXPECT_EQ(line_series("low", "out"), from_json["line_out 1"]);
  EXPECT_EQ(line_series(R"(middle \"m\")", "in"), counter.line_counts()[0].in);
  EXPECT_EQ(line_series(R"(middle \"m\")", "out"), counter.line_counts()[0].out);
  EXPECT_EQ(line_series("low", "in"), counter.line_counts()[1].in);
  EXPECT_EQ(line_series("low", "out"), counter.line_counts()[1].out);
  EXPECT_GT(counter.line_counts()[0].in + counter.line_counts()[0].out, 10);
  const auto zone = [&](const char* event) {
    return value_of(text, std::string(R"(rtmot_zone_events_total{stream="3",zone="left",event=")") +
                              event + "\"}");
  };
  EXPECT_EQ(zone("enter"), from_json["zone_enter 0"]);
  EXPECT_EQ(zone("exit"), from_json["zone_exit 0"]);
  EXPECT_EQ(zone("dwell"), from_json["zone_dwell 0"]);
  EXPECT_EQ(zone("enter"), counter.zone_counts()[0].entered);
  EXPECT_GT(zone("dwell"), 0.0);
  EXPECT_EQ(value_of(text, R"(rtmot_zone_occupancy{stream="3",zone="left"})"),
            counter.zone_counts()[0].occupancy);
  // The web page's status (docs/web.md) reads the same counters.
  const nlohmann::json status = metrics.status()["events"].at(0);
  EXPECT_EQ(status["stream"], 3);
  EXPECT_EQ(status["lines"][0]["name"], "middle \"m\"");
  EXPECT_EQ(status["lines"][0]["in"].get<double>(), line_series(R"(middle \"m\")", "in"));
  EXPECT_EQ(status["lines"][0]["out"].get<double>(), line_series(R"(middle \"m\")", "out"));
  EXPECT_EQ(status["lines"][1]["in"].get<double>(), line_series("low", "in"));
  EXPECT_EQ(status["zones"][0]["enter"].get<double>(), zone("enter"));
  EXPECT_EQ(status["zones"][0]["dwell"].get<double>(), zone("dwell"));
  EXPECT_EQ(status["zones"][0]["occupancy"], counter.zone_counts()[0].occupancy);
}

// The page's counts per class: the rtmot tracker on PETS09-S2L1's detections, every other track
// called a car (class 3), the rest people (1); each line's and zone's classes add up to its total,
// both classes are there, and a class beyond the labels' columns is in the totals only.
TEST(EventMetrics, CountsPerClassAddUpToTheTotals) {
  RTMOT_REQUIRE_FILE(S2L1Tracking::dir() / "det" / "det.txt");
  S2L1Tracking s2l1;
  const auto& info = s2l1.info;
  const auto& detections = s2l1.detections;
  auto& tracker = s2l1.tracker;
  events::EventsConfig config;
  config.lines.push_back({"middle", {{384.0, 0.0}, {384.0, 576.0}}, true});
  config.zones.push_back({"left", {{38, 172}, {346, 172}, {346, 547}, {38, 547}}, 5.0});
  events::EventCounter counter(config);
  const messages::ClassLabelFn labels = [](int id) -> std::string_view {
    return id == 1 ? "person" : id == 3 ? "car" : "";
  };
  EventMetrics event_metrics({{3, {"middle"}, {"left"}}}, 4, labels);  // columns 0..3
  EventMetricsSink sink(event_metrics);
  messages::FrameResult frame;
  frame.stream_id = 3;
  int beyond = 0;
  for (int f = 1; f <= info.length; ++f) {
    const double time = (f - 1) / info.frame_rate;
    const auto& reports = tracker.update(detections.at(f), time);
    frame.frame_number = f;
    frame.tracks.assign(reports.begin(), reports.end());
    for (auto& track : frame.tracks) track.class_id = track.id % 2 == 0 ? 1 : 3;
    const auto& decided = counter.update(frame.tracks, time);
    frame.events.assign(decided.begin(), decided.end());
    // One crossing of a class the labels do not have (id 7): counted in the total only.
    if (beyond == 0 && !frame.events.empty() && events::is_line_event(frame.events[0].kind)) {
      frame.events[0].class_id = 7;
      beyond = frame.events[0].kind == events::EventKind::line_in ? 1 : -1;
    }
    sink.write(frame);
  }
  ASSERT_NE(beyond, 0);
  const nlohmann::json status = event_metrics.status().at(0);
  const nlohmann::json& line = status["lines"][0];
  const nlohmann::json& classes = line["classes"];
  ASSERT_TRUE(classes.contains("person") && classes.contains("car")) << line.dump();
  EXPECT_EQ(classes.size(), 2U) << line.dump();
  EXPECT_EQ(
      classes["person"]["in"].get<int>() + classes["car"]["in"].get<int>() + (beyond == 1 ? 1 : 0),
      line["in"].get<int>());
  EXPECT_EQ(classes["person"]["out"].get<int>() + classes["car"]["out"].get<int>() +
                (beyond == -1 ? 1 : 0),
            line["out"].get<int>());
  EXPECT_EQ(line["in"].get<int>(), counter.line_counts()[0].in);
  const nlohmann::json& zone = status["zones"][0];
  ASSERT_TRUE(zone["classes"].contains("person") && zone["classes"].contains("car")) << zone.dump();
  EXPECT_EQ(
      zone["classes"]["person"]["enter"].get<int>() + zone["classes"]["car"]["enter"].get<int>(),
      zone["enter"].get<int>());
  EXPECT_EQ(
      zone["classes"]["person"]["exit"].get<int>() + zone["classes"]["car"]["exit"].get<int>(),
      zone["exit"].get<int>());
}

// A name made without the YAML reader's UTF-8 check (a caller of its own) cannot break the page:
// a byte that is not UTF-8 becomes U+FFFD, so Prometheus still reads every series.
TEST(EventMetrics, ANameThatIsNotUtf8BecomesAReplacementCharacter) {
  EventMetrics event_metrics({{3,
                               {"Entr\xE9"
                                "e"},
                               {"caf\xC3"}}});
  std::string text;
  event_metrics.render(text);
  EXPECT_EQ(first_invalid_utf8(text), std::nullopt) << text;
  EXPECT_NE(text.find("line=\"Entr\xEF\xBF\xBD"
                      "e\""),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("zone=\"caf\xEF\xBF\xBD\""), std::string::npos) << text;
}

}  // namespace
}  // namespace rtmot::outputs
