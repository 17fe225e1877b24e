#include "runner/run_config.hpp"

#include <yaml-cpp/yaml.h>

#include <optional>
#include <set>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "detector/dnn_backend.hpp"
#include "runner/host_port.hpp"
#include "runner/sequence_clock_source.hpp"
#include "runner/yaml_section.hpp"
#include "tracker/presets.hpp"

namespace rtmot::runner {
namespace {

// The documented ranges (docs/config.md) of the keys outside `tracker:`.
constexpr int kMaxImageSide = 16384;
constexpr double kMaxFps = 1000.0;
constexpr double kMaxLatencyMs = 3'600'000.0;
constexpr int kMaxThreads = 256;
constexpr int kMaxClassId = 1000;
constexpr double kMaxStatsInterval = 86'400.0;
constexpr std::int64_t kMaxFrames = 1'000'000'000'000;
// A configuration is a page of text: a bigger file is not one.
constexpr std::uint64_t kMaxConfigBytes = 1 << 20;

void read_source(Section section, SourceConfig& source) {
  section.read("uri", source.uri);
  read_checked(section, "width", source.width, within(0, kMaxImageSide),
               "a size in [0, " + std::to_string(kMaxImageSide) + "]");
  read_checked(section, "height", source.height, within(0, kMaxImageSide),
               "a size in [0, " + std::to_string(kMaxImageSide) + "]");
  read_checked(section, "fps", source.fps, within(0.0, kMaxFps), "a rate in [0, 1000]");
  section.reject_unknown();
}

void read_playback(Section section, PlaybackConfig& playback) {
  std::string mode;
  if (section.read("mode", mode)) {
    const auto parsed = pipeline::parse_playback_mode(mode);
    if (!parsed) {
      section.fail(*section.find("mode"), "mode",
                   "expected " + pipeline::playback_mode_alternatives());
    }
    playback.mode = *parsed;
  }
  read_checked(
      section, "latency_ms", playback.latency_ms,
      [](double v) { return v > 0.0 && v <= kMaxLatencyMs; }, "a latency in (0, 3600000]");
  section.reject_unknown();
}

void read_detector(Section section, DetectorConfig& detector) {
  read_checked(
      section, "kind", detector.kind,
      [](const std::string& v) { return v == "ssd" || v == "replay"; }, "ssd or replay");
  section.read("model", detector.model);
  section.read("anchors", detector.anchors);
  read_checked(
      section, "backend", detector.backend,
      [](const std::string& v) { return detector::parse_backend_request(v).has_value(); },
      "auto, cpu or cuda");
  read_checked(
      section, "fp16", detector.fp16,
      [](const std::string& v) { return detector::parse_fp16_request(v).has_value(); },
      "auto, on or off");
  read_checked(section, "threads", detector.threads, within(0, kMaxThreads), "a count in [0, 256]");
  read_checked(section, "score_threshold", detector.score_threshold, unit_interval,
               "a score in [0, 1]");
  read_checked(section, "nms_threshold", detector.nms_threshold, unit_interval, "an IoU in [0, 1]");
  read_checked(
      section, "classes", detector.classes,
      [](const std::vector<int>& ids) {
        for (const int id : ids) {
          if (id < 0 || id > kMaxClassId) return false;
        }
        return true;
      },
      "class ids in [0, 1000]");
  section.read("det_file", detector.det_file);
  section.reject_unknown();
}

template <typename Parse, typename Enum>
bool read_enum(Section& section, const std::string& key, Parse parse,
               const std::string& expectation, Enum& out) {
  std::string text;
  if (!section.read(key, text)) return false;
  const auto parsed = parse(text);
  if (!parsed) section.fail(*section.find(key), key, "expected " + expectation);
  out = *parsed;
  return true;
}

void read_tracker(Section section, tracker::TrackerConfig& config) {
  // Without a preset the pipeline starts from the default (best measured) one, as `rtmot track`.
  std::string preset{tracker::default_preset_name()};
  section.read("preset", preset);
  const auto found = tracker::find_preset(preset);
  if (!found) {
    section.fail(*section.find("preset"), "preset", "expected one of: " + tracker::preset_names());
  }
  config = *found;
  config.frame_rate = 0.0;  // still "from the source" unless set below
  config.image_width = 0.F;
  config.image_height = 0.F;
  // A preset's detection_threshold was tuned on MOTChallenge detection scores (Faster R-CNN); in
  // the pipeline the detector's own score_threshold is the one confidence cut unless this is set
  // below.
  config.detection_threshold = 0.F;
  read_enum(section, "predictor", tracker::parse_predictor, "kalman, stationary or particle",
            config.predictor);
  const bool affinity_given = read_enum(section, "affinity", tracker::parse_affinity,
                                        "iou, linear or exponential", config.affinity);
  const bool threshold_given = section.read("affinity_threshold", config.affinity_threshold);
  // A new affinity without its own threshold gets that affinity's usual one.
  if (affinity_given && !threshold_given)
    config.affinity_threshold = tracker::default_threshold(config.affinity);
  read_checked(section, "detection_threshold", config.detection_threshold, unit_interval,
               "a score in [0, 1]");
  read_checked(
      section, "max_age", config.max_age, [](int v) { return v >= 0; }, "an age >= 0");
  read_checked(
      section, "min_hits", config.min_hits, [](int v) { return v >= 0; }, "a count >= 0");
  read_enum(section, "time_step", tracker::parse_time_step, "per_update or elapsed",
            config.time_step);
  read_checked(
      section, "frame_rate", config.frame_rate, [](double v) { return v > 0.0; }, "a rate > 0");
  read_checked(
      section, "image_width", config.image_width, [](float v) { return v > 0.F; }, "a width > 0");
  read_checked(
      section, "image_height", config.image_height, [](float v) { return v > 0.F; },
      "a height > 0");
  section.read("second_round", config.second_round);
  read_checked(section, "low_score", config.low_score, unit_interval, "a score in [0, 1]");
  section.read("observation_centric_reupdate", config.observation_centric_reupdate);
  section.read("time_widened_gate", config.time_widened_gate);
  read_checked(
      section, "particle_count", config.particle_count, [](int v) { return v > 0; }, "a count > 0");
  std::int64_t seed = static_cast<std::int64_t>(config.seed);
  read_checked(
      section, "seed", seed, [](std::int64_t v) { return v >= 0; }, "a seed >= 0");
  config.seed = static_cast<std::uint64_t>(seed);
  read_checked(
      section, "max_tracks", config.max_tracks, [](int v) { return v > 0; }, "a count > 0");
  read_checked(
      section, "max_detections", config.max_detections, [](int v) { return v > 0; }, "a count > 0");
  section.reject_unknown();
}

void read_output(Section section, OutputConfig& output) {
  if (section.read("udp", output.udp) && !output.udp.empty()) {
    const YAML::Node value = *section.find("udp");
    parse_host_port(output.udp, section.file(), line_of(value), section.field("udp"),
                    ExitCode::bad_input);
  }
  section.read("binary_file", output.binary_file);
  section.read("jsonl_file", output.jsonl_file);
  section.read("video_file", output.video_file);
  section.read("report_file", output.report_file);
  section.reject_unknown();
}

// CPU_SETSIZE: the most CPUs pthread_setaffinity_np can name. A CPU this machine lacks is not a
// configuration error (the same file runs on several boards): the thread runs unpinned, logged.
constexpr int max_cpu = 1023;

void read_stage_thread(Section section, pipeline::StageThread& thread) {
  read_checked(
      section, "cpu", thread.cpu, [](int v) { return v >= -1 && v <= max_cpu; },
      "a CPU number in 0..1023, or -1 for any");
  read_checked(
      section, "fifo_priority", thread.fifo_priority, [](int v) { return v >= 0 && v <= 99; },
      "a SCHED_FIFO priority in 1..99, or 0 for normal scheduling");
  section.reject_unknown();
}

void read_threads(Section section, const std::string& file_name, pipeline::StageThreads& threads) {
  const auto stage = [&](const char* name, pipeline::StageThread& thread) {
    read_stage_thread(Section(section.child(name), file_name, section.field(name)), thread);
  };
  stage("capture", threads.capture);
  stage("detect", threads.detect);
  stage("track", threads.track);
  stage("sink", threads.sink);
  section.reject_unknown();
}

}  // namespace

RunConfig parse_run_config(const std::string& yaml_text, const std::string& file_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& error) {
    throw InputError(file_name, error.mark.line + 1, "", "not valid YAML: " + error.msg);
  }
  RunConfig config;
  config.file = file_name;
  config.tracker.frame_rate = 0.0;
  config.tracker.image_width = 0.F;
  config.tracker.image_height = 0.F;

  Section top(root, file_name, "");
  if (root.IsNull()) throw InputError(file_name, 0, "", "the configuration is empty");
  read_source(Section(top.child("source"), file_name, "source"), config.source);
  read_playback(Section(top.child("playback"), file_name, "playback"), config.playback);
  read_detector(Section(top.child("detector"), file_name, "detector"), config.detector);
  read_tracker(Section(top.child("tracker"), file_name, "tracker"), config.tracker);
  read_output(Section(top.child("output"), file_name, "output"), config.output);
  read_threads(Section(top.child("threads"), file_name, "threads"), file_name, config.threads);
  read_checked(top, "stats_interval_s", config.stats_interval_s, within(0.0, kMaxStatsInterval),
               "an interval in [0, 86400]");
  top.read("stream_id", config.stream_id);
  read_checked(top, "max_frames", config.max_frames, within<std::int64_t>(0, kMaxFrames),
               "a count in [0, 10^12]");
  top.reject_unknown();
  return config;
}

RunConfig load_run_config(const std::string& path) {
  return parse_run_config(read_text_file(path, kMaxConfigBytes), path);
}

void validate(const RunConfig& config) {
  const auto missing = [&](const std::string& field, const std::string& problem) {
    throw InputError(config.file, 0, field, problem);
  };
  if (config.source.uri.empty()) missing("source.uri", "no source given (or use --source URI)");
  if (config.detector.kind == "ssd" && config.detector.model.empty()) {
    missing("detector.model", "the ssd detector needs a model file");
  }
  if (config.detector.kind == "replay" && config.detector.det_file.empty()) {
    missing("detector.det_file", "the replay detector needs a det.txt file");
  }
  if (is_sequence_uri(config.source.uri)) {
    if (config.detector.kind == "ssd") {
      missing("detector.kind", "a mot-seq:// source has no images: use the replay detector");
    }
    if (!config.output.video_file.empty()) {
      missing("output.video_file", "a mot-seq:// source has no images to annotate");
    }
  }
}

}  // namespace rtmot::runner
