#include "runner/run_config.hpp"

#include <yaml-cpp/yaml.h>

#include <optional>
#include <set>

#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/input_path.hpp"
#include "detector/dnn_backend.hpp"
#include "outputs/mqtt_uri.hpp"
#include "outputs/overlay.hpp"
#include "outputs/video_target.hpp"
#include "platform/host_port.hpp"
#include "runner/host_port.hpp"
#include "runner/sequence_clock_source.hpp"
#include "runner/yaml_section.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker_options.hpp"

namespace rtmot::runner {
namespace {

// The documented ranges (docs/config.md) of the keys outside `tracker:`.
constexpr int kMaxImageSide = 16384;
constexpr double kMaxLatencyMs = 3'600'000.0;
constexpr int kMaxThreads = 256;
constexpr int kMaxClassId = 1000;
constexpr double kMaxStatsInterval = 86'400.0;
constexpr std::int64_t kMaxFrames = 1'000'000'000'000;
// A configuration is a page of text: a bigger file is not one.
constexpr std::uint64_t kMaxConfigBytes = 1 << 20;

void read_source(Section section, SourceConfig& source) {
  section.read("uri", source.uri);
  source.events =
      events::read_events_spec(section.child("events"), section.file(), section.field("events"));
  read_checked(section, "width", source.width, within(0, kMaxImageSide),
               "a size in [0, " + std::to_string(kMaxImageSide) + "]");
  read_checked(section, "height", source.height, within(0, kMaxImageSide),
               "a size in [0, " + std::to_string(kMaxImageSide) + "]");
  read_checked(
      section, "fps", source.fps, [](double fps) { return fps == 0.0 || is_frame_rate(fps); },
      "0 (the source's rate) or a rate in " + frame_rate_range());
  read_checked(
      section, "stream_id", source.stream_id,
      [](std::int64_t v) { return v >= 0 && v <= std::int64_t{0xFFFFFFFF}; },
      "a stream id in 0..4294967295");
  section.reject_unknown();
}

// `sources:` a list whose entries are a URI or a mapping with the keys of `source`.
void read_sources(Section& top, const std::string& file_name, std::vector<SourceConfig>& sources) {
  const YAML::Node list = top.child("sources");
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) top.fail(list, "sources", "expected a list of sources");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node entry = list[i];
    const std::string field = "sources[" + std::to_string(i) + "]";
    SourceConfig source;
    if (entry.IsScalar()) {
      source.uri = entry.Scalar();
    } else {
      read_source(Section(entry, file_name, field), source);
    }
    if (source.uri.empty()) throw InputError(file_name, line_of(entry), field, "no uri given");
    sources.push_back(source);
  }
  if (sources.empty()) top.fail(list, "sources", "the list is empty");
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
      detector::backend_request_names());
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
  // No preset assumes a score scale (the default's cut is relative to the stream's own scores),
  // so the preset applies here as in `rtmot track`; the detector's score_threshold is the
  // detector's own cut, made before the tracker sees anything.
  // Every other key is an option of the one table (tracker/tracker_options.hpp), read as text so
  // that the YAML file and the command line accept exactly the same values.
  for (const auto& option : tracker::tracker_options()) {
    std::string text;
    if (!section.read(option.name, text)) continue;
    if (!option.set(config, text)) {
      section.fail(*section.find(option.name), option.name, "expected " + option.expected);
    }
  }
  section.reject_unknown();
  // Ranges that only fail together (frame_rate may still come from the source: checked later).
  tracker::TrackerConfig check = config;
  if (check.frame_rate <= 0.0) check.frame_rate = 1.0;
  if (const auto problem = tracker::config_problem(check)) {
    for (const char* key : {"particle_count", "max_tracks"}) {
      if (const auto where = section.find(key)) section.fail(*where, key, *problem);
    }
    section.fail(YAML::Node{}, "", *problem);
  }
}

void read_output(Section section, OutputConfig& output) {
  if (section.read("udp", output.udp) && !output.udp.empty()) {
    const YAML::Node value = *section.find("udp");
    parse_host_port(output.udp, section.file(), line_of(value), section.field("udp"),
                    ExitCode::bad_input);
  }
  section.read("binary_file", output.binary_file);
  section.read("jsonl_file", output.jsonl_file);
  section.read("mqtt", output.mqtt);
  section.read("video_file", output.video_file);
  section.read("overlay", output.overlay);
  section.read("report_file", output.report_file);
  read_checked(
      section, "metrics_port", output.metrics_port, [](int v) { return v >= 0 && v <= 65535; },
      "a TCP port 0..65535 (0 = off)");
  if (section.read("metrics_bind", output.metrics_bind)) {
    std::string problem;
    const auto address = platform::parse_bind_address(output.metrics_bind, problem);
    if (!address) section.fail(*section.find("metrics_bind"), "metrics_bind", problem);
    output.metrics_bind = *address;
  }
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
  read_sources(top, file_name, config.sources);
  if (!config.sources.empty() && !config.source.uri.empty()) {
    top.fail(*top.find("sources"), "sources", "give either source.uri or sources, not both");
  }
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

namespace {

// The folder a configuration's relative input paths start from (common/input_path.hpp); none for
// the command line's defaults.
std::filesystem::path base_dir_of(const RunConfig& config) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(config.file, error)) return {};
  return std::filesystem::absolute(config.file, error).parent_path();
}

// Inputs only (the model, det.txt, video files); outputs stay relative to the working directory.
void resolve_input_paths(RunConfig& config) {
  const auto base = base_dir_of(config);
  std::string tried;
  if (!config.detector.model.empty())
    config.detector.model = resolve_input_path(config.detector.model, base, "models", tried);
  if (!config.detector.det_file.empty())
    config.detector.det_file = resolve_input_path(config.detector.det_file, base, "", tried);
  const auto resolve_source = [&](SourceConfig& source) {
    if (!source.uri.empty() && source.uri.find("://") == std::string::npos)
      source.uri = resolve_input_path(source.uri, base, "", tried);
  };
  resolve_source(config.source);
  for (SourceConfig& source : config.sources) resolve_source(source);
}

}  // namespace

RunConfig default_run_config() {
  RunConfig config = parse_run_config("tracker: {}\n", "(defaults)");
  config.file = "(command line)";
  config.detector.model = "models/ssdlite_mobilenet_v2_coco.onnx";
  resolve_input_paths(config);  // the working directory's models/, else the installed one
  return config;
}

RunConfig load_run_config(const std::string& path) {
  // A bare name not here (`--config jetson-csi.yaml`) may be one of the installed configs.
  std::string tried;
  const std::string found = resolve_input_path(path, {}, "configs", tried);
  RunConfig config = parse_run_config(read_text_file(found, kMaxConfigBytes), found);
  resolve_input_paths(config);
  return config;
}

std::vector<SourceConfig> source_list(const RunConfig& config) {
  return config.sources.empty() ? std::vector<SourceConfig>{config.source} : config.sources;
}

std::uint32_t stream_id_of(const RunConfig& config, std::size_t index) {
  const SourceConfig& source = config.sources.empty() ? config.source : config.sources.at(index);
  if (source.stream_id >= 0) return static_cast<std::uint32_t>(source.stream_id);
  return config.stream_id + static_cast<std::uint32_t>(index);
}

void validate(const RunConfig& config) {
  const auto missing = [&](const std::string& field, const std::string& problem) {
    throw InputError(config.file, 0, field, problem);
  };
  if (config.source.uri.empty() && config.sources.empty()) {
    missing("source.uri", "no source given (or use --source URI)");
  }
  const auto sources = source_list(config);
  std::set<std::uint32_t> stream_ids;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    if (!stream_ids.insert(stream_id_of(config, i)).second) {
      missing("sources[" + std::to_string(i) + "].stream_id",
              "stream id " + std::to_string(stream_id_of(config, i)) + " is used twice");
    }
  }
  if (sources.size() > 1 && !config.output.video_file.empty()) {
    missing("output.video_file", "the annotated video needs a single source");
  }
  if (config.detector.kind == "ssd" && config.detector.model.empty()) {
    missing("detector.model", "the ssd detector needs a model file");
  }
  if (config.detector.kind == "replay" && config.detector.det_file.empty()) {
    missing("detector.det_file", "the replay detector needs a det.txt file");
  }
  for (const SourceConfig& source : sources) {
    if (!is_sequence_uri(source.uri)) continue;
    if (config.detector.kind == "ssd") {
      missing("detector.kind", "a mot-seq:// source has no images: use the replay detector");
    }
    if (!config.output.video_file.empty()) {
      missing("output.video_file", "a mot-seq:// source has no images to annotate");
    }
  }
  // Every output is checked here, before the model loads: a typo costs no start-up time.
  std::string problem;
  if (!config.output.udp.empty() && !platform::parse_host_port(config.output.udp, problem)) {
    missing("output.udp",
            "expected HOST:PORT or [IPV6]:PORT, got '" + config.output.udp + "': " + problem);
  }
  if (!config.output.mqtt.empty() && !outputs::parse_mqtt_uri(config.output.mqtt, problem)) {
    missing("output.mqtt", "'" + config.output.mqtt + "': " + problem);
  }
  if (!config.output.video_file.empty() &&
      !outputs::parse_video_target(config.output.video_file, problem)) {
    missing("output.video_file", "'" + config.output.video_file + "': " + problem);
  }
  if (!outputs::parse_overlay_flags(config.output.overlay, problem)) {
    missing("output.overlay", problem);
  }
  if (config.detector.kind == "ssd") {
    // Say where it was looked for: "not found" alone sent users to fetch a model they had.
    std::string tried;
    resolve_input_path(config.detector.model, base_dir_of(config), "models", tried);
    if (!tried.empty()) {
      throw InputError(config.file, 0, "detector.model",
                       "model file '" + config.detector.model + "' not found; tried " + tried +
                           " (relative paths in a config file start at its folder; run "
                           "scripts/fetch_model.sh to fetch the model)",
                       ExitCode::bad_model);
    }
  }
}

}  // namespace rtmot::runner
