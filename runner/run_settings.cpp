#include "runner/run_settings.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "common/checked_number.hpp"
#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "detector/tile_request.hpp"
#include "platform/video_uri.hpp"
#include "runner/yaml_document.hpp"

namespace rtmot::runner {
namespace {

// The documented ranges (docs/config.md).
constexpr int kMaxImageSide = 16384;
constexpr int kMaxThreads = 256;
constexpr int kMaxLoops = 1'000'000;
// Each lane holds a detector of its own (on CUDA two networks and their buffers); past 2-3 lanes
// nothing is left to overlap (docs/gpu.md).
constexpr int kMaxInFlight = 4;
constexpr std::int64_t kMaxFrames = 1'000'000'000'000;
// CPU_SETSIZE: the most CPUs pthread_setaffinity_np can name. A CPU this machine lacks is not a
// configuration error (the same file runs on several boards): the thread runs unpinned, logged.
constexpr int kMaxCpu = 1023;

template <typename T>
using Field = std::function<T&(RunConfig&)>;

// A number read by common/checked_number (finite, whole where a count is meant, in its range),
// stored into the field as T.
template <typename T, typename Range, typename Parse>
RunSetting number(std::string key, std::string flag, std::string doc, Range range, Field<T> field,
                  Parse parse) {
  std::string expected = range.expected();
  return {std::move(key),
          std::move(flag),
          std::move(doc),
          std::move(expected),
          false,
          [range, field, parse](RunConfig& c, std::string_view text, std::string&) {
            const auto value = parse(text, range);
            if (value) field(c) = static_cast<T>(*value);
            return value.has_value();
          }};
}

template <typename T>
RunSetting real(std::string key, std::string flag, std::string doc, RealRange range,
                Field<T> field) {
  return number<T>(std::move(key), std::move(flag), std::move(doc), range, std::move(field),
                   &parse_real);
}

template <typename T>
RunSetting integer(std::string key, std::string flag, std::string doc, IntegerRange range,
                   Field<T> field) {
  return number<T>(std::move(key), std::move(flag), std::move(doc), range, std::move(field),
                   &parse_integer);
}

// A broker and a topic to publish to (no wildcards: outputs/mqtt_uri.hpp).
std::optional<outputs::MqttUri> publish_uri(const std::string& text, std::string& problem) {
  return outputs::parse_mqtt_uri(text, problem, outputs::MqttTopicUse::publish);
}

// A frame rate (common/frame_rate.hpp: one range for every rate), or 0 for "the source's own".
RunSetting frame_rate_or_zero(std::string key, std::string flag, std::string doc,
                              Field<double> field) {
  return {std::move(key),
          std::move(flag),
          std::move(doc),
          "0 (the source's rate) or a rate in " + frame_rate_range(),
          false,
          [field](RunConfig& c, std::string_view text, std::string&) {
            const auto value = parse_real(text, {0.0, kMaxFrameRate});
            if (!value || (*value != 0.0 && !is_frame_rate(*value))) return false;
            field(c) = *value;
            return true;
          }};
}

// A switch: YAML's own booleans (true/false), on the command line too.
RunSetting boolean(std::string key, std::string flag, std::string doc, Field<bool> field) {
  return {std::move(key),
          std::move(flag),
          std::move(doc),
          "true or false",
          false,
          [field](RunConfig& c, std::string_view text, std::string&) {
            if (text != "true" && text != "false") return false;
            field(c) = text == "true";
            return true;
          }};
}

// A path or URI taken as written (opened and checked when the run starts).
RunSetting text(std::string key, std::string flag, std::string doc, Field<std::string> field) {
  return {std::move(key),
          std::move(flag),
          std::move(doc),
          "a path",
          false,
          [field](RunConfig& c, std::string_view text, std::string&) {
            field(c) = std::string(text);
            return true;
          }};
}

// A value with its own parser: `parse(text, problem)` returns an optional of the field's type.
template <typename T, typename Parse>
RunSetting parsed(std::string key, std::string flag, std::string doc, std::string expected,
                  Parse parse, Field<T> field) {
  return {std::move(key),
          std::move(flag),
          std::move(doc),
          std::move(expected),
          false,
          [parse, field](RunConfig& c, std::string_view text, std::string& problem) {
            auto value = parse(std::string(text), problem);
            if (value) field(c) = std::move(*value);
            return value.has_value();
          }};
}

template <typename Names, typename T>
RunSetting named(std::string key, std::string flag, std::string doc, const Names& names,
                 Field<T> field) {
  return parsed<T>(
      std::move(key), std::move(flag), std::move(doc), names.alternatives(),
      [&names](const std::string& text, std::string&) { return names.parse(text); }, field);
}

std::optional<HostPort> host_port(const std::string& text, std::string& problem) {
  const auto parsed = platform::parse_host_port(text, problem);
  if (!parsed) problem = "expected HOST:PORT or [IPV6]:PORT, got '" + text + "': " + problem;
  return parsed;
}

// An output that may be off: empty text turns it off, anything else is `parse`d (its problem
// quoted with the text unless `parse` quotes it itself).
template <typename Parse>
auto off_or(Parse parse, bool quote = true) {
  return [parse, quote](const std::string& text, std::string& problem) {
    using Value = typename decltype(parse(text, problem))::value_type;
    if (text.empty()) return std::optional<std::optional<Value>>(std::optional<Value>{});
    auto value = parse(text, problem);
    if (!value) {
      if (quote) problem = "'" + text + "': " + problem;
      return std::optional<std::optional<Value>>{};
    }
    return std::optional<std::optional<Value>>(std::move(value));
  };
}

// The source's `events:` section on the command line, written as in the file (a YAML flow
// mapping) and read by the file's own reader (events/events_yaml.hpp): one syntax of lines and
// zones, one set of checks. For every source: the flags come after --source made the list.
RunSetting events_setting() {
  return {"source.events",
          "--events",
          "lines, zones and dwell counted on every source's tracks (docs/events.md)",
          "a YAML mapping as the events: section, e.g. '{lines: [{name: door, units: fraction, "
          "from: [0.5, 0], to: [0.5, 1]}]}'",
          false,
          [](RunConfig& c, std::string_view text, std::string& problem) {
            try {
              const YAML::Node node = load_one_document(std::string(text), "--events");
              if (!node.IsMap()) {
                problem = "expected a mapping of lines, zones, ... in braces: {lines: [...]}";
                return false;
              }
              const events::EventsSpec spec = events::read_events_spec(node, "--events");
              c.source.events = spec;
              for (SourceConfig& source : c.sources) source.events = spec;
              return true;
            } catch (const InputError& e) {
              problem = (e.field().empty() ? "" : "'" + e.field() + "': ") + e.problem();
            }
            return false;
          }};
}

std::vector<RunSetting> source_settings() {
  const auto side = IntegerRange{0, kMaxImageSide};
  return {
      text("source.uri", "",
           "what to track: a file or folder, " + platform::source_uri_schemes() + ", mot-seq://",
           [](RunConfig& c) -> std::string& { return c.source.uri; }),
      // The flags are jetson-inference's (--input-width, ...), for every source of the run.
      integer<int>("source.width", "--input-width", "requested camera width; 0 = the source's",
                   side, [](RunConfig& c) -> int& { return c.source.width; }),
      integer<int>("source.height", "--input-height", "requested camera height; 0 = the source's",
                   side, [](RunConfig& c) -> int& { return c.source.height; }),
      frame_rate_or_zero("source.fps", "--input-rate", "requested camera rate; 0 = the source's",
                         [](RunConfig& c) -> double& { return c.source.fps; }),
      integer<int>("source.loop", "--input-loop",
                   "play a file again when it ends: N more times, -1 = for ever, 0 = once",
                   {-1, kMaxLoops}, [](RunConfig& c) -> int& { return c.source.loop; }),
      named("source.flip", "--input-flip", "turn or mirror every frame before detection",
            platform::kOrientationNames,
            Field<platform::Orientation>([](RunConfig & c) -> auto& { return c.source.flip; })),
      integer<std::int64_t>(
          "source.stream_id", "", "this source's stream id (default: stream_id + its index)",
          {0, 0xFFFFFFFF}, [](RunConfig& c) -> std::int64_t& { return c.source.stream_id; }),
      events_setting(),
  };
}

std::vector<RunSetting> playback_settings() {
  return {
      parsed<PlaybackMode>(
          "playback.mode", "--playback", "how recorded frames are released to the detector",
          pipeline::playback_mode_alternatives(),
          [](const std::string& t, std::string&) { return pipeline::parse_playback_mode(t); },
          [](RunConfig& c) -> PlaybackMode& { return c.playback.mode; }),
      real<double>("playback.latency_ms", "--latency-ms",
                   "simulated detector latency (simulated mode)", {0.0, 3'600'000.0, true},
                   [](RunConfig& c) -> double& { return c.playback.latency_ms; }),
  };
}

std::vector<RunSetting> detector_settings() {
  const RealRange unit{0.0, 1.0};
  RunSetting classes = parsed<std::vector<std::string>>(
      "detector.classes", "--classes",
      "classes to keep: names of the model's labels (COCO's for the bundled model: person,car) "
      "or column numbers (1,3); all = every class",
      "class names or column numbers of the model's labels, or all", parse_classes,
      [](RunConfig& c) -> std::vector<std::string>& { return c.detector.classes; });
  classes.list = true;
  return {
      named("detector.kind", "", "ssd (the model on every frame) or replay (a det.txt file)",
            kDetectorKindNames,
            Field<DetectorKind>([](RunConfig& c) -> DetectorKind& { return c.detector.kind; })),
      text("detector.model", "--model", "ssd: the ONNX model (the flag also sets kind ssd)",
           [](RunConfig& c) -> std::string& { return c.detector.model; }),
      text("detector.anchors", "", "ssd: the anchors CSV; empty = beside the model",
           [](RunConfig& c) -> std::string& { return c.detector.anchors; }),
      text("detector.int8_ranges", "",
           "backend xnnpack-int8: the calibrated activation ranges; empty = "
           "configs/int8/<model name>.ranges",
           [](RunConfig& c) -> std::string& { return c.detector.int8_ranges; }),
      named("detector.backend", "--backend", "the engine that runs the model",
            detector::kBackendNames,
            Field<detector::BackendRequest>(
                [](RunConfig& c) -> detector::BackendRequest& { return c.detector.backend; })),
      parsed<detector::Fp16Request>(
          "detector.fp16", "--fp16", "half precision on CUDA (auto: on Jetson boards)",
          detector::kFp16Names.alternatives(),
          [](const std::string& t, std::string&) { return detector::parse_fp16_request(t); },
          [](RunConfig& c) -> detector::Fp16Request& { return c.detector.fp16; }),
      real<float>("detector.score_threshold", "--threshold",
                  "the detector's score cut, before the tracker", unit,
                  [](RunConfig& c) -> float& { return c.detector.score_threshold; }),
      real<float>("detector.nms_threshold", "--nms-threshold", "non-maximum suppression IoU", unit,
                  [](RunConfig& c) -> float& { return c.detector.nms_threshold; }),
      integer<int>("detector.threads", "--detector-threads",
                   "the detector's CPU threads; 0 = every CPU this process may use",
                   {0, kMaxThreads}, [](RunConfig& c) -> int& { return c.detector.threads; }),
      parsed<int>(
          "detector.in_flight", "--in-flight",
          "batches in flight in the detect stage, each on a detector of its own; auto = 3 on CUDA "
          "(fp32 and fp16), 1 otherwise",
          "auto or an integer in [1, " + std::to_string(kMaxInFlight) + "]",
          [](const std::string& t, std::string&) -> std::optional<int> {
            if (t == "auto") return 0;
            const auto value = parse_integer(t, {1, kMaxInFlight});
            if (!value) return std::nullopt;
            return static_cast<int>(*value);
          },
          [](RunConfig& c) -> int& { return c.detector.in_flight; }),
      std::move(classes),
      parsed<detector::TileRequest>(
          "detector.tiles", "--tiles",
          "ssd: a large frame seen in overlapping tiles near the network's input size, with the "
          "whole frame, as one batch: off, auto (by frame size, playback mode and measured speed) "
          "or a grid (docs/tiling.md)",
          "off, auto or COLUMNSxROWS with 1.." + std::to_string(detector::kMaxTileSide) +
              " of each (e.g. 3x2)",
          [](const std::string& t, std::string& problem) {
            return detector::parse_tile_request(t, problem);
          },
          [](RunConfig& c) -> detector::TileRequest& { return c.detector.tiles; }),
      real<float>("detector.tile_overlap", "--tile-overlap",
                  "ssd: the share of a tile that its neighbours also see", {0.0, 0.5},
                  [](RunConfig& c) -> float& { return c.detector.tile_overlap; }),
      real<float>("detector.tile_threshold", "--tile-threshold",
                  "ssd: the score cut of the tiles' boxes (the whole frame's is score_threshold)",
                  unit, [](RunConfig& c) -> float& { return c.detector.tile_threshold; }),
      boolean("detector.plausible_shapes", "--plausible-shapes",
              "ssd: drop boxes of shapes their class does not have, e.g. a person wider than tall "
              "(docs/tiling.md)",
              [](RunConfig& c) -> bool& { return c.detector.plausible_shapes; }),
      boolean("detector.appearance", "--appearance",
              "a colour signature of each detection from the image, for the tracker's appearance "
              "gate and weight (tracker.appearance_gate, appearance_weight; docs/appearance.md); "
              "off: the tracker sees boxes only",
              [](RunConfig& c) -> bool& { return c.detector.appearance; }),
      boolean("detector.follow_image", "--follow-image",
              "between detections, follow each track's box in the image (optical flow on a gray "
              "thumbnail of every camera frame): the frames the detector skipped get observed "
              "boxes and the next association starts where the image showed the tracks "
              "(docs/full-rate.md)",
              [](RunConfig& c) -> bool& { return c.detector.follow_image; }),
      text("detector.det_file", "--det-file",
           "replay: a MOTChallenge det.txt (the flag also sets kind replay)",
           [](RunConfig& c) -> std::string& { return c.detector.det_file; }),
  };
}

std::vector<RunSetting> output_settings() {
  return {
      parsed<std::optional<HostPort>>(
          "output.udp", "--udp", "send track messages to HOST:PORT or [IPV6]:PORT",
          "HOST:PORT or [IPV6]:PORT", off_or(host_port, false),
          [](RunConfig& c) -> std::optional<HostPort>& { return c.output.udp; }),
      text("output.binary_file", "--binary", "write binary track messages to this file",
           [](RunConfig& c) -> std::string& { return c.output.binary_file; }),
      text("output.jsonl_file", "--jsonl", "write track messages as JSON lines to this file",
           [](RunConfig& c) -> std::string& { return c.output.jsonl_file; }),
      parsed<std::optional<outputs::MqttUri>>(
          "output.mqtt", "--mqtt", "publish track messages to an MQTT broker",
          outputs::mqtt_uri_syntax(), off_or(publish_uri),
          [](RunConfig& c) -> std::optional<outputs::MqttUri>& { return c.output.mqtt; }),
      parsed<std::optional<outputs::VideoTarget>>(
          "output.video_file", "--video-out", "the annotated video",
          "FILE.mp4/.mkv, rtsp://[ADDRESS]:PORT/NAME, rtp://HOST:PORT or display://N",
          off_or(outputs::parse_video_target),
          [](RunConfig& c) -> std::optional<outputs::VideoTarget>& { return c.output.video; }),
      parsed<outputs::VideoCodec>(
          "output.video_codec", "--video-codec",
          "the video's codec (browsers play H.264; H.265 plays in VLC, ffplay, GStreamer)",
          outputs::kVideoCodecNames.alternatives(),
          [](const std::string& t, std::string&) { return outputs::kVideoCodecNames.parse(t); },
          [](RunConfig& c) -> outputs::VideoCodec& { return c.output.video_encoding.codec; }),
      parsed<std::string>(
          "output.video_encoder", "--video-encoder",
          "the video's encoder: auto = the board's hardware encoder if present, else software",
          outputs::encoder_request_alternatives(), outputs::parse_encoder_request,
          [](RunConfig& c) -> std::string& { return c.output.video_encoding.encoder; }),
      integer<int>("output.video_bitrate", "--bitrate", "the video's bitrate in kbit/s",
                   {outputs::kMinVideoBitrateKbps, outputs::kMaxVideoBitrateKbps},
                   [](RunConfig& c) -> int& { return c.output.video_encoding.bitrate_kbps; }),
      parsed<outputs::OverlayFlags>(
          "output.overlay", "--overlay", "what the video shows (comma-separated)",
          outputs::overlay_flag_names() + " (comma-separated), or none",
          outputs::parse_overlay_flags,
          [](RunConfig& c) -> outputs::OverlayFlags& { return c.output.overlay; }),
      text("output.report_file", "--report", "write the final report as JSON to this file",
           [](RunConfig& c) -> std::string& { return c.output.report_file; }),
      text("output.mot_results", "--mot-results",
           "write MOTChallenge results per source into this folder: NAME.txt and NAME.frames "
           "(the frames processed), for rtmot eval",
           [](RunConfig& c) -> std::string& { return c.output.mot_results; }),
      boolean("output.mot_detections", "--mot-detections",
              "with output.mot_results: also NAME.det.txt there, each processed frame's "
              "detections as the tracker got them (a MOTChallenge det.txt: --det-file replays "
              "it; docs/scoring.md)",
              [](RunConfig& c) -> bool& { return c.output.mot_detections; }),
      boolean("output.full_rate", "--full-rate",
              "a message for every camera frame: those the detector skipped carry each track's "
              "predicted box, flagged predicted (docs/full-rate.md)",
              [](RunConfig& c) -> bool& { return c.output.full_rate; }),
      integer<int>("output.metrics_port", "--metrics-port",
                   "serve Prometheus metrics on this TCP port; 0 = off", {0, 65535},
                   [](RunConfig& c) -> int& { return c.output.metrics_port; }),
      parsed<std::string>("output.metrics_bind", "--metrics-bind",
                          "the address the metrics endpoint listens on", "an IPv4 or IPv6 address",
                          platform::parse_bind_address,
                          [](RunConfig& c) -> std::string& { return c.output.metrics_bind; }),
      real<double>("output.metrics_linger_s", "--metrics-linger",
                   "after the run, keep serving the final metrics this many seconds (a scraper "
                   "sees the last counts; SIGINT/SIGTERM ends it); 0 = off",
                   {0.0, 86'400.0},
                   [](RunConfig& c) -> double& { return c.output.metrics_linger_s; }),
      integer<int>("output.web_port", "--web-port",
                   "serve the operator's page (live picture, counts, health; docs/web.md) on this "
                   "TCP port; 0 = off",
                   {0, 65535}, [](RunConfig& c) -> int& { return c.output.web_port; }),
      parsed<std::string>("output.web_bind", "--web-bind",
                          "the address the page listens on (0.0.0.0: every network; docs/web.md's "
                          "threat model first)",
                          "an IPv4 or IPv6 address", platform::parse_bind_address,
                          [](RunConfig& c) -> std::string& { return c.output.web_bind; }),
      text("output.web_token_file", "--web-token-file",
           "a file holding the token the page's writes (saving lines and zones) must carry; "
           "without it the page only reads",
           [](RunConfig& c) -> std::string& { return c.output.web_token_file; }),
      text("output.web_save_to", "--web-save-to",
           "the page's saves (lines, zones, settings) go to this file, a copy of the "
           "configuration file with the change, instead of the configuration file itself",
           [](RunConfig& c) -> std::string& { return c.output.web_save_to; }),
  };
}

std::vector<RunSetting> thread_settings() {
  using Stage = pipeline::StageThread pipeline::StageThreads::*;
  const std::pair<const char*, Stage> stages[] = {{"capture", &pipeline::StageThreads::capture},
                                                  {"detect", &pipeline::StageThreads::detect},
                                                  {"track", &pipeline::StageThreads::track},
                                                  {"sink", &pipeline::StageThreads::sink}};
  std::vector<RunSetting> settings;
  for (const auto& [name, stage] : stages) {
    const std::string prefix = std::string("threads.") + name;
    const Stage member = stage;
    RunSetting cpu = integer<int>(
        prefix + ".cpu", "", "pin the stage's thread to this CPU; -1 = any", {-1, kMaxCpu},
        [member](RunConfig& c) -> int& { return (c.threads.*member).cpu; });
    RunSetting fifo = integer<int>(
        prefix + ".fifo_priority", "", "SCHED_FIFO priority 1..99; 0 = normal scheduling", {0, 99},
        [member](RunConfig& c) -> int& { return (c.threads.*member).fifo_priority; });
    settings.push_back(std::move(cpu));
    settings.push_back(std::move(fifo));
  }
  return settings;
}

std::vector<RunSetting> top_settings() {
  return {
      real<double>("stats_interval_s", "--stats-interval",
                   "seconds between progress lines; 0 = none", {0.0, 86'400.0},
                   [](RunConfig& c) -> double& { return c.stats_interval_s; }),
      integer<std::uint32_t>("stream_id", "--stream-id", "stream id in every message",
                             {0, 0xFFFFFFFF},
                             [](RunConfig& c) -> std::uint32_t& { return c.stream_id; }),
      integer<std::int64_t>("max_frames", "--max-frames",
                            "stop after this many captured frames; 0 = no limit", {0, kMaxFrames},
                            [](RunConfig& c) -> std::int64_t& { return c.max_frames; }),
  };
}

std::vector<RunSetting> make_table() {
  std::vector<RunSetting> table;
  for (auto part : {source_settings(), playback_settings(), detector_settings(), output_settings(),
                    thread_settings(), top_settings()}) {
    for (auto& setting : part) table.push_back(std::move(setting));
  }
  return table;
}

}  // namespace

const std::vector<RunSetting>& run_settings() {
  static const std::vector<RunSetting> table = make_table();
  return table;
}

const RunSetting* find_run_setting(std::string_view key) {
  for (const auto& setting : run_settings()) {
    if (setting.key == key) return &setting;
  }
  return nullptr;
}

std::string refusal(const RunSetting& setting, std::string_view text, const std::string& problem) {
  if (!problem.empty()) return problem;
  return "'" + std::string(text) + "': expected " + setting.expected;
}

// The words only: what they name depends on the model's labels, known once every setting is
// (runner/class_choice.hpp resolves them).
std::optional<std::vector<std::string>> parse_classes(std::string_view text, std::string& problem) {
  std::vector<std::string> classes;
  if (text == "all") return classes;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view word = text.substr(start, comma - start);
    if (word.empty() || word == "all") {
      problem = "'" + std::string(text) +
                "': expected class names or column numbers separated by commas (person,car or "
                "1,3), or all alone";
      return std::nullopt;
    }
    classes.emplace_back(word);
    start = comma + 1;
  }
  return classes;
}

}  // namespace rtmot::runner
