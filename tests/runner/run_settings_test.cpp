// The settings' one table (runner/run_settings.hpp): the YAML file and the command line read it
// alike, a preset means the same wherever it is given, and docs/config.md shows the table as it is.
#include "runner/run_settings.hpp"

#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "common/input_error.hpp"
#include "docs_table.hpp"
#include "runner/run_flags.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"

namespace rtmot::runner {
namespace {

// The configuration `rtmot run` makes of `args` (a command line after `run`) on top of `yaml`.
RunConfig with_flags(const std::string& yaml, const std::string& args) {
  RunConfig config = parse_run_config(yaml, "base.yaml");
  CLI::App app;
  RunFlags flags;
  flags.add_to(app);
  app.parse(args, false);
  flags.apply(config);
  return config;
}

void expect_same_tracker(const tracker::TrackerConfig& a, const tracker::TrackerConfig& b) {
  EXPECT_EQ(a.predictor, b.predictor);
  EXPECT_EQ(a.affinity, b.affinity);
  EXPECT_EQ(a.affinity_threshold, b.affinity_threshold);
  EXPECT_EQ(a.detection_threshold, b.detection_threshold);
  EXPECT_EQ(a.score_range_cut, b.score_range_cut);
  EXPECT_EQ(a.max_age, b.max_age);
  EXPECT_EQ(a.min_hits, b.min_hits);
  EXPECT_EQ(a.time_step, b.time_step);
  EXPECT_EQ(a.second_round, b.second_round);
  EXPECT_EQ(a.low_score, b.low_score);
  EXPECT_EQ(a.birth_threshold, b.birth_threshold);
  EXPECT_EQ(a.strong_birth_range_cut, b.strong_birth_range_cut);
  EXPECT_EQ(a.confirm_by_duration, b.confirm_by_duration);
  EXPECT_EQ(a.keep_confirmation, b.keep_confirmation);
  EXPECT_EQ(a.tentative_dies_on_miss, b.tentative_dies_on_miss);
  EXPECT_EQ(a.second_round_threshold, b.second_round_threshold);
  EXPECT_EQ(a.noise_gate_factor, b.noise_gate_factor);
  EXPECT_EQ(a.frame_rate, b.frame_rate);
  EXPECT_EQ(a.image_width, b.image_width);
  EXPECT_EQ(a.image_height, b.image_height);
}

// Issue 18: `--preset bytetrack` zeroed the score cut that `tracker: {preset: bytetrack}` kept.
TEST(RunSettings, PresetOnTheCommandLineEqualsPresetInTheFile) {
  for (const std::string name : {"sort", "rtmot", "bytetrack"}) {
    SCOPED_TRACE(name);
    const RunConfig from_file =
        parse_run_config("tracker:\n  preset: " + name + "\n", "preset.yaml");
    const RunConfig from_flag = with_flags("stream_id: 0\n", "--preset " + name);
    expect_same_tracker(from_file.tracker, from_flag.tracker);
    const auto preset = tracker::find_preset(name);
    ASSERT_TRUE(preset.has_value());
    EXPECT_EQ(from_flag.tracker.detection_threshold, preset->detection_threshold)
        << "the preset's own score cut, as `rtmot track --preset` uses it";
    EXPECT_EQ(from_flag.tracker.frame_rate, 0.0) << "from the source";
  }
  // The flag replaces the file's tracker section, keys and all.
  const RunConfig replaced = with_flags("tracker:\n  max_age: 7\n", "--preset sort");
  EXPECT_EQ(replaced.tracker.max_age, tracker::find_preset("sort")->max_age);
}

// A source's flag (--input-flip, --input-loop, --input-width...) is for every source of the run:
// the file's `sources:` list and several --source alike (issue 22).
TEST(RunSettings, SourceFlagsApplyToEverySource) {
  const RunConfig listed = with_flags("sources:\n  - a.mp4\n  - {uri: b.mp4, loop: 1}\n",
                                      "--input-flip rotate-180 --input-loop -1 --input-width 640");
  ASSERT_EQ(listed.sources.size(), 2U);
  for (const SourceConfig& source : listed.sources) {
    EXPECT_EQ(source.flip, platform::Orientation::rotate_180) << source.uri;
    EXPECT_EQ(source.loop, -1) << source.uri;
    EXPECT_EQ(source.width, 640) << source.uri;
  }
  const RunConfig repeated =
      with_flags("stream_id: 0\n", "--source a.mp4 --source b.mp4 --input-flip horizontal");
  ASSERT_EQ(repeated.sources.size(), 2U);
  for (const SourceConfig& source : repeated.sources) {
    EXPECT_EQ(source.flip, platform::Orientation::horizontal) << source.uri;
  }
  const RunConfig file_only =
      parse_run_config("source:\n  uri: a.mp4\n  flip: counterclockwise\n  loop: 3\n", "f.yaml");
  EXPECT_EQ(file_only.source.flip, platform::Orientation::counterclockwise);
  EXPECT_EQ(file_only.source.loop, 3);
}

TEST(RunSettings, FlagsAndFileKeysGiveTheSameValues) {
  const RunConfig from_file = parse_run_config(
      "detector:\n  score_threshold: 0.25\n  classes: [person, car]\n  backend: cpu\n"
      "output:\n  udp: '[::1]:5600'\n  metrics_port: 9100\n  metrics_bind: '::1'\n"
      "playback:\n  mode: simulated\n  latency_ms: 40\nmax_frames: 12\n",
      "f.yaml");
  const RunConfig from_flags = with_flags(
      "stream_id: 0\n",
      "--threshold 0.25 --classes person,car --backend cpu --udp [::1]:5600 --metrics-port 9100 "
      "--metrics-bind ::1 --playback simulated --latency-ms 40 --max-frames 12");
  EXPECT_EQ(from_file.detector.score_threshold, from_flags.detector.score_threshold);
  EXPECT_EQ(from_file.detector.classes, (std::vector<std::string>{"person", "car"}));
  EXPECT_EQ(from_flags.detector.classes, from_file.detector.classes);
  EXPECT_EQ(from_flags.detector.backend, detector::BackendRequest::cpu);
  ASSERT_TRUE(from_flags.output.udp && from_file.output.udp);
  EXPECT_EQ(from_flags.output.udp->host, "::1");
  EXPECT_EQ(from_file.output.udp->port, from_flags.output.udp->port);
  EXPECT_EQ(from_flags.output.metrics_bind, from_file.output.metrics_bind);
  EXPECT_EQ(from_flags.playback.mode, PlaybackMode::simulated);
  EXPECT_EQ(from_flags.playback.latency_ms, from_file.playback.latency_ms);
  EXPECT_EQ(from_flags.max_frames, 12);
}

// A refused flag names the flag and is a usage error (exit 2), never the YAML key it sets (exit 3).
TEST(RunSettings, RefusedFlagsNameTheFlag) {
  for (const auto& [flag, value] :
       std::vector<std::pair<std::string, std::string>>{{"--threshold", "nan"},
                                                        {"--video-out", "out/x.avi"},
                                                        {"--mqtt", "tcp://broker/t"},
                                                        {"--overlay", "boxes"},
                                                        {"--udp", "999.999.1.1:5600"},
                                                        {"--metrics-bind", "999.999.1.1"},
                                                        {"--classes", "person,,car"},
                                                        {"--max-frames", "-1"},
                                                        {"--preset", "deepsort"}}) {
    SCOPED_TRACE(flag + " " + value);
    try {
      with_flags("stream_id: 0\n", flag + " " + value);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), flag);
      EXPECT_EQ(error.exit_code(), ExitCode::usage);
    }
  }
}

// Issue 24: lines and zones on the command line are the file's `events:` section written inline,
// read by the same reader: the same spec as the file's, for every source of the run.
TEST(RunSettings, EventsFlagIsTheFilesEventsSection) {
  const std::string section =
      "{dwell_s: 5, lines: [{name: door, units: fraction, from: [0.5, 0], to: [0.5, 1], in: "
      "right}], zones: [{name: hall, points: [[10, 10], [90, 10], [90, 90], [10, 90]]}]}";
  const RunConfig from_file = parse_run_config("source:\n  events: " + section + "\n", "e.yaml");
  const RunConfig from_flag = with_flags("sources: [a.mp4, b.mp4]\n", "--events '" + section + "'");
  ASSERT_EQ(from_flag.sources.size(), 2U);
  for (const auto& events :
       {from_flag.source.events, from_flag.sources[0].events, from_flag.sources[1].events}) {
    const events::EventsConfig& got = events.written;
    const events::EventsConfig& want = from_file.source.events.written;
    ASSERT_EQ(got.lines.size(), 1U);
    EXPECT_EQ(got.lines[0].name, want.lines[0].name);
    EXPECT_EQ(got.lines[0].segment.to.y, 1.0);
    EXPECT_FALSE(got.lines[0].in_is_left);
    EXPECT_EQ(events.line_units, from_file.source.events.line_units);
    ASSERT_EQ(got.zones.size(), 1U);
    EXPECT_EQ(got.zones[0].polygon.size(), 4U);
    EXPECT_EQ(got.zones[0].dwell_seconds, 5.0);
  }
  for (const std::string bad : {"lines", "'{lines: ['", "'{lines: [{from: [0, 0], to: [1, 1]}]}'",
                                "'{zones: [{name: z, points: [[0, 0], [1, 1]]}]}'"}) {
    SCOPED_TRACE(bad);
    try {
      with_flags("stream_id: 0\n", "--events " + bad);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), "--events");
      EXPECT_EQ(error.exit_code(), ExitCode::usage);
    }
  }
}

// An enum's names come from its one table: every name sets its value, by flag and by file, and the
// accepted values the docs and errors show are the table's.
TEST(RunSettings, NamedValuesComeFromTheirTables) {
  for (const auto& [fp16, name] : detector::kFp16Names.entries()) {
    SCOPED_TRACE(std::string(name));
    EXPECT_EQ(with_flags("stream_id: 0\n", "--fp16 " + std::string(name)).detector.fp16, fp16);
    EXPECT_EQ(
        parse_run_config("detector:\n  fp16: " + std::string(name) + "\n", "f.yaml").detector.fp16,
        fp16);
  }
  // YAML's booleans read as on and off.
  EXPECT_EQ(with_flags("detector:\n  fp16: true\n", "").detector.fp16, detector::Fp16Request::on);
  EXPECT_EQ(find_run_setting("detector.fp16")->expected, "auto, on or off");
  EXPECT_EQ(find_run_setting("detector.fp16")->expected, detector::kFp16Names.alternatives());

  for (const auto& [payload, name] : outputs::kMqttPayloadNames.entries()) {
    SCOPED_TRACE(std::string(name));
    const auto config =
        with_flags("stream_id: 0\n", "--mqtt mqtt://broker/t?format=" + std::string(name));
    ASSERT_TRUE(config.output.mqtt.has_value());
    EXPECT_EQ(config.output.mqtt->payload, payload);
  }
  EXPECT_EQ(find_run_setting("output.mqtt")->expected,
            "mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json]");
}

TEST(RunSettings, EveryKeyAndFlagIsDeclaredOnce) {
  std::set<std::string> keys;
  std::set<std::string> flags{"--config", "--preset", "--source"};
  for (const auto& setting : run_settings()) {
    EXPECT_TRUE(keys.insert(setting.key).second) << setting.key;
    if (!setting.flag.empty()) {
      EXPECT_TRUE(flags.insert(setting.flag).second) << setting.flag;
    }
    EXPECT_FALSE(setting.doc.empty()) << setting.key;
    EXPECT_FALSE(setting.expected.empty()) << setting.key;
  }
}

// The reference table of docs/config.md, as the settings' table makes it.
std::string markdown_table() {
  std::ostringstream text;
  text << "| key | flag | accepted | meaning |\n| --- | --- | --- | --- |\n";
  for (const auto& setting : run_settings()) {
    text << "| `" << setting.key << "` | "
         << (setting.flag.empty() ? "–" : "`" + setting.flag + "`") << " | "
         << test::markdown_cell(setting.expected) << " | " << setting.doc << " |\n";
  }
  return text.str();
}

constexpr const char* kBegin =
    "<!-- settings-table: generated from runner/run_settings.cpp by tests/runner/"
    "run_settings_test.cpp (RTMOT_UPDATE_DOCS=1 rewrites it) -->\n";
constexpr const char* kEnd = "<!-- end settings-table -->\n";

// docs/config.md cannot drift from the table: the test fails until the docs show it as it is.
TEST(RunSettings, DocsShowTheTableAsItIs) {
  const test::DocsText docs = test::check_generated_table(test::source_path("docs/config.md"),
                                                          kBegin, kEnd, markdown_table());
  ASSERT_TRUE(docs.found);
  // Every key also has its hand-written row (defaults, details) in its section's table.
  for (const auto& setting : run_settings()) {
    const std::string name = setting.key.substr(setting.key.rfind('.') + 1);
    EXPECT_NE(docs.text.find("`" + name + "`", docs.table_end), std::string::npos)
        << setting.key << " has no row of its own below the reference table";
  }
}

}  // namespace
}  // namespace rtmot::runner
