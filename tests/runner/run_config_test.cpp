// The run configuration: every shipped config loads, and every kind of mistake names file, line
// and field.
#include "runner/run_config.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/input_error.hpp"
#include "runner/class_choice.hpp"
#include "runner/run_setup.hpp"
#include "runner/source_factory.hpp"
#include "shared_data.hpp"

namespace rtmot::pipeline {
namespace {

const char* const full = R"(source:
  uri: data/vtest.avi
  width: 640
  height: 480
  fps: 10
playback:
  mode: simulated
  latency_ms: 250
detector:
  kind: ssd
  model: models/ssdlite_mobilenet_v2_coco.onnx
  backend: cpu
  fp16: false
  score_threshold: 0.4
  nms_threshold: 0.5
  classes: [1, 3]
tracker:
  preset: sort
  max_age: 3
  affinity: linear
output:
  udp: 127.0.0.1:5600
  jsonl_file: out.jsonl
  report_file: report.json
stats_interval_s: 2
stream_id: 7
max_frames: 100
)";

TEST(RunConfig, ReadsEverySection) {
  const runner::RunConfig config = runner::parse_run_config(full, "full.yaml");
  EXPECT_EQ(config.source.uri, "data/vtest.avi");
  EXPECT_EQ(config.source.width, 640);
  EXPECT_DOUBLE_EQ(config.source.fps, 10.0);
  EXPECT_EQ(config.playback.mode, PlaybackMode::simulated);
  EXPECT_DOUBLE_EQ(config.playback.latency_ms, 250.0);
  EXPECT_EQ(config.detector.backend, detector::BackendRequest::cpu);
  EXPECT_EQ(config.detector.fp16, detector::Fp16Request::off);
  EXPECT_FLOAT_EQ(config.detector.score_threshold, 0.4F);
  EXPECT_EQ(config.detector.classes, (std::vector<std::string>{"1", "3"}));
  EXPECT_EQ(runner::resolve_classes(config, detector::LabelTable::coco()),
            (std::vector<int>{1, 3}));
  EXPECT_EQ(config.lines.at("detector.classes"), 16);
  EXPECT_EQ(config.tracker.max_age, 3);
  EXPECT_EQ(config.tracker.min_hits, 3);
  EXPECT_EQ(config.tracker.affinity, tracker::AffinityKind::linear);
  EXPECT_DOUBLE_EQ(config.tracker.affinity_threshold,
                   tracker::default_threshold(tracker::AffinityKind::linear));
  EXPECT_DOUBLE_EQ(config.tracker.frame_rate, 0.0) << "unset: taken from the source";
  ASSERT_TRUE(config.output.udp.has_value());
  EXPECT_EQ(config.output.udp->host, "127.0.0.1");
  EXPECT_EQ(config.output.udp->port, 5600);
  EXPECT_EQ(config.output.report_file, "report.json");
  EXPECT_DOUBLE_EQ(config.stats_interval_s, 2.0);
  EXPECT_EQ(config.stream_id, 7U);
  EXPECT_EQ(config.max_frames, 100);
}

TEST(RunConfig, EveryShippedConfigLoadsAndValidates) {
  const auto folder = test::source_path("configs");
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    runner::RunConfig config = runner::load_run_config(entry.path().string());
    // Where the web page's saves go: the file itself (the defaults have none: below).
    EXPECT_EQ(config.loaded_from, entry.path().string());
    if (config.source.uri.empty() && config.sources.empty()) {
      // A config for data rtmot does not ship (mot.yaml: MOTChallenge's) says in its header what
      // to pass; with that it validates.
      std::ifstream file(entry.path());
      const std::string text((std::istreambuf_iterator<char>(file)), {});
      EXPECT_NE(text.find("--source mot-seq://"), std::string::npos) << "no source, no usage line";
      const auto sequence = test::shared_path("data/mot15-train/TUD-Campus");
      config.source.uri = "mot-seq://" + sequence.string();
      config.detector.det_file = (sequence / "det/det.txt").string();
    }
    EXPECT_NO_THROW(validate(config));
    ++count;
  }
  EXPECT_GE(count, 5) << "desktop, jetson-csi, jetson-usb, tx1-replay, mot";
  // A run without --config has no file to save the page's lines into (it applies them only).
  EXPECT_EQ(runner::default_run_config().loaded_from, "");
}

// Parses `yaml` expecting an InputError at `line` naming `field`.
void expect_error(const std::string& yaml, int line, const std::string& field) {
  try {
    runner::parse_run_config(yaml, "bad.yaml");
    FAIL() << "accepted:\n" << yaml;
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "bad.yaml");
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_EQ(error.field(), field) << error.what();
    EXPECT_EQ(error.exit_code(), ExitCode::bad_input);
  }
}

TEST(RunConfig, UnknownKeysAreRejectedWithTheirLine) {
  expect_error("source:\n  uri: a.avi\n  fsp: 10\n", 3, "source.fsp");
  expect_error("source:\n  uri: a.avi\nsauce: 1\n", 3, "sauce");
  expect_error("tracker:\n  max_age: 2\n  maxage: 3\n", 3, "tracker.maxage");
}

TEST(RunConfig, WrongTypesNameLineAndField) {
  expect_error("source:\n  uri: a.avi\n  width: wide\n", 3, "source.width");
  expect_error("detector:\n  fp16: maybe\n", 2, "detector.fp16");
  expect_error("detector:\n  threads: [2]\n", 2, "detector.threads");
  expect_error("detector:\n  classes: 1\n", 2, "detector.classes");
  expect_error("detector:\n  classes: [1, '']\n", 2, "detector.classes");
  expect_error("source: [1, 2]\n", 1, "source");
  expect_error("stats_interval_s:\n", 1, "stats_interval_s");
}

TEST(RunConfig, BadValuesNameLineAndField) {
  expect_error("playback:\n  mode: fast\n", 2, "playback.mode");
  expect_error("playback:\n  latency_ms: 0\n", 2, "playback.latency_ms");
  expect_error("\n\ndetector:\n  backend: tpu\n", 4, "detector.backend");
  expect_error("detector:\n  score_threshold: 1.5\n", 2, "detector.score_threshold");
  expect_error("tracker:\n  predictor: magic\n", 2, "tracker.predictor");
  expect_error("tracker:\n  preset: deepsort\n", 2, "tracker.preset");
  expect_error("tracker:\n  min_hits: -1\n", 2, "tracker.min_hits");
  expect_error("max_frames: -5\n", 1, "max_frames");
}

TEST(RunConfig, StageThreadsAreReadAndCheckedPerStage) {
  const runner::RunConfig config = runner::parse_run_config(
      "threads:\n  capture: {cpu: 0, fifo_priority: 20}\n  detect:\n    cpu: 1\n", "t.yaml");
  EXPECT_EQ(config.threads.capture.cpu, 0);
  EXPECT_EQ(config.threads.capture.fifo_priority, 20);
  EXPECT_EQ(config.threads.detect.cpu, 1);
  EXPECT_EQ(config.threads.detect.fifo_priority, 0);
  EXPECT_EQ(config.threads.track.cpu, -1) << "unset: any CPU";
  EXPECT_EQ(runner::make_options(config).threads.capture.fifo_priority, 20);
  expect_error("threads:\n  detect:\n    fifo_priority: 100\n", 3, "threads.detect.fifo_priority");
  expect_error("threads:\n  sink: {cpu: -2}\n", 2, "threads.sink.cpu");
  expect_error("threads:\n  tracker: {cpu: 0}\n", 2, "threads.tracker");
  expect_error("threads:\n  track: {core: 0}\n", 2, "threads.track.core");
}

TEST(RunConfig, SourcesListGivesEachItsStreamId) {
  const runner::RunConfig config = runner::parse_run_config(
      "stream_id: 10\nsources:\n  - a.avi\n  - {uri: rtsp://cam/1, width: 640, stream_id: 3}\n"
      "  - uri: b.avi\n",
      "s.yaml");
  const auto sources = runner::source_list(config);
  ASSERT_EQ(sources.size(), 3U);
  EXPECT_EQ(sources[0].uri, "a.avi");
  EXPECT_EQ(sources[1].uri, "rtsp://cam/1");
  EXPECT_EQ(sources[1].width, 640);
  EXPECT_EQ(runner::stream_id_of(config, 0), 10U) << "top-level id + index";
  EXPECT_EQ(runner::stream_id_of(config, 1), 3U) << "its own";
  EXPECT_EQ(runner::stream_id_of(config, 2), 12U);
  EXPECT_EQ(
      runner::source_list(runner::parse_run_config("source: {uri: x.avi}\n", "one.yaml")).size(),
      1U);
}

TEST(RunConfig, SourcesListMistakesNameTheEntry) {
  expect_error("sources: a.avi\n", 1, "sources");
  expect_error("sources: []\n", 1, "sources");
  expect_error("sources:\n  - a.avi\n  - {uri: b.avi, fsp: 3}\n", 3, "sources[1].fsp");
  expect_error("sources:\n  - {width: 3}\n", 2, "sources[0]");
  expect_error("source: {uri: a.avi}\nsources: [b.avi]\n", 2, "sources");
  const auto invalid = [](const std::string& yaml, const std::string& field) {
    runner::RunConfig config = runner::parse_run_config(yaml, "v.yaml");
    config.detector.model = "m.onnx";
    try {
      runner::validate(config);
      ADD_FAILURE() << "expected an InputError for " << field;
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), field) << error.what();
    }
  };
  invalid("sources:\n  - {uri: a.avi, stream_id: 1}\n  - {uri: b.avi, stream_id: 1}\n",
          "sources[1].stream_id");
  invalid("sources: [a.avi, b.avi]\noutput: {video_file: v.mp4}\n", "output.video_file");
}

// Every tracker key is read through the one options table: values a typed conversion would take
// (NaN, a count written as a float, a count that would allocate gigabytes) are refused where read.
TEST(RunConfig, TrackerRangesAreCheckedWhereRead) {
  expect_error("tracker:\n  affinity_threshold: .nan\n", 2, "tracker.affinity_threshold");
  expect_error("tracker:\n  max_tracks: 2147483647\n", 2, "tracker.max_tracks");
  expect_error("tracker:\n  max_tracks: 1e6\n", 2, "tracker.max_tracks");
  expect_error("tracker:\n  particle_count: 2147483647\n", 2, "tracker.particle_count");
  expect_error("tracker:\n  affinity: exp\n", 2, "tracker.affinity");
  expect_error("tracker:\n  max_tracks: 10000\n  predictor: particle\n  particle_count: 5000\n", 4,
               "tracker.particle_count");
}

TEST(RunConfig, EveryTrackerOptionCanBeSetFromYaml) {
  const auto config = runner::parse_run_config(
      "tracker:\n  preset: sort\n  confirmed_tracks_first: true\n  confirm_by_duration: true\n"
      "  min_coast_updates: 2\n  time_step: elapsed\n",
      "t.yaml");
  EXPECT_TRUE(config.tracker.confirmed_tracks_first);
  EXPECT_TRUE(config.tracker.confirm_by_duration);
  EXPECT_EQ(config.tracker.min_coast_updates, 2);
  EXPECT_EQ(config.tracker.time_step, tracker::TimeStep::elapsed);
}

TEST(RunConfig, MalformedYamlNamesTheLine) {
  expect_error("source:\n  uri: [a.avi\n", 3, "");
}

// Issue 23, class 11: yaml-cpp's Load() read the first document and dropped the rest silently.
TEST(RunConfig, ASecondDocumentIsAnErrorNamingItsLine) {
  expect_error("source:\n  uri: a.avi\n---\nsource:\n  uri: b.avi\n", 4, "");
  expect_error("stream_id: 1\n---\n", 3, "");
}

TEST(RunConfig, ClassesTakeNamesOrIdsAsTheCommandLineDoes) {
  const auto config = runner::parse_run_config("detector:\n  classes: [person, 3]\n", "c.yaml");
  EXPECT_EQ(runner::resolve_classes(config, detector::LabelTable::coco()),
            (std::vector<int>{1, 3}));
  EXPECT_TRUE(
      runner::parse_run_config("detector:\n  classes: []\n", "c.yaml").detector.classes.empty())
      << "an empty list keeps every class";
}

TEST(RunConfig, ValidateNamesWhatIsMissing) {
  runner::RunConfig config = runner::parse_run_config("detector:\n  kind: replay\n", "x.yaml");
  try {
    validate(config);
    FAIL();
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "source.uri");
  }
  config.source.uri = "mot-seq://x";
  try {
    validate(config);
    FAIL();
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "detector.det_file");
  }
}

TEST(RunConfig, MissingFileNamesIt) {
  try {
    runner::load_run_config("/nonexistent/run.yaml");
    FAIL();
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "/nonexistent/run.yaml");
  }
}

TEST(RunConfig, PlaybackModesRoundTrip) {
  for (const auto mode :
       {PlaybackMode::every_frame, PlaybackMode::realtime, PlaybackMode::simulated}) {
    EXPECT_EQ(parse_playback_mode(to_string(mode)), mode);
  }
  EXPECT_EQ(parse_playback_mode("every_frame"), std::nullopt);
}

}  // namespace
}  // namespace rtmot::pipeline

namespace rtmot::runner {
namespace {

// --input-width on a file is a camera's capture mode asked of a file: said in one line, not
// silently without effect; a camera takes it, and nothing asked says nothing (issue 22).
TEST(CaptureRequest, OnlyCamerasTakeASizeAndRateOthersSaySo) {
  platform::SourceOptions asked;
  asked.width = 640;
  EXPECT_EQ(ignored_capture_request("data/vtest.avi", asked),
            "data/vtest.avi: source.width/height/fps (--input-width/-height/-rate) choose a "
            "camera's capture mode (v4l2://, csi://); a recording plays at its own size and rate "
            "(file://PATH?fps=N re-times one whose header is wrong)");
  // A stream's cold start uses them until it appears.
  EXPECT_EQ(ignored_capture_request("rtsp://cam/stream", asked), "");
  EXPECT_EQ(ignored_capture_request("v4l2:///dev/video0", asked), "");
  EXPECT_EQ(ignored_capture_request("csi://0", asked), "");
  EXPECT_EQ(ignored_capture_request("data/vtest.avi", platform::SourceOptions{}), "");
  platform::SourceOptions rate;
  rate.fps = 15.0;
  EXPECT_NE(ignored_capture_request("test://ball", rate), "");
}

// Classes are names of the model's labels: checked once the model is known, with the line the
// file gave them on. COCO's for the bundled model.
TEST(ClassChoice, ClassesTheLabelsDoNotHaveNameFileLineAndField) {
  const auto expect_refused = [](const std::string& yaml, const std::string& word) {
    const auto config = parse_run_config(yaml, "bad.yaml");
    try {
      resolve_classes(config, detector::LabelTable::coco());
      ADD_FAILURE() << "accepted:\n" << yaml;
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), "bad.yaml");
      EXPECT_EQ(error.line(), 3) << error.what();
      EXPECT_EQ(error.field(), "detector.classes");
      EXPECT_EQ(error.exit_code(), ExitCode::usage);
      EXPECT_NE(std::string(error.what())
                    .find("'" + word + "' is not a class of the model's labels (COCO's table"),
                std::string::npos)
          << error.what();
    }
  };
  expect_refused("detector:\n  kind: ssd\n  classes: [1, unicorn]\n", "unicorn");
  expect_refused("detector:\n  kind: ssd\n  classes: [1, 91]\n", "91");
  expect_refused("detector:\n  kind: ssd\n  classes: [12]\n", "12");  // COCO reserved, unnamed
}

// A model with its own labels file (its .model.yaml names it): its names, not COCO's.
TEST(ClassChoice, ClassesAreTheModelsOwnLabels) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("rtmot-class-choice-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "fruit.onnx") << "not read here";
  std::ofstream(dir / "fruit.model.yaml") << "layout: decoded\nlabels: fruit.labels.txt\n";
  std::ofstream(dir / "fruit.labels.txt") << "BACKGROUND\napple\nbanana\n";
  auto config =
      parse_run_config("detector:\n  kind: ssd\n  model: " + (dir / "fruit.onnx").string() +
                           "\n  classes: [banana, 1]\n",
                       "fruit.yaml");
  const auto labels = run_labels(config);
  EXPECT_EQ(labels->columns(), 3);
  EXPECT_EQ(resolve_classes(config, *labels), (std::vector<int>{2, 1}));
  config.detector.classes = {"person"};  // COCO's column 1, not this model's
  try {
    resolve_classes(config, *labels);
    ADD_FAILURE() << "person accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find((dir / "fruit.labels.txt").string()),
              std::string::npos)
        << error.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rtmot::runner
