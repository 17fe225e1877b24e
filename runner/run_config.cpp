#include "runner/run_config.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "common/input_error.hpp"
#include "detector/dnn_backend.hpp"
#include "tracker/presets.hpp"
#include "runner/sequence_clock_source.hpp"

namespace rtmot::runner {
namespace {

int line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

std::string type_name(int) {
  return "an integer";
}
std::string type_name(std::int64_t) {
  return "an integer";
}
std::string type_name(std::uint32_t) {
  return "a non-negative integer";
}
std::string type_name(double) {
  return "a number";
}
std::string type_name(float) {
  return "a number";
}
std::string type_name(bool) {
  return "true or false";
}
std::string type_name(const std::string&) {
  return "a string";
}
std::string type_name(const std::vector<int>&) {
  return "a list of integers";
}

// One mapping of the file: reads the keys it knows and rejects the rest.
class Section {
 public:
  Section(const YAML::Node& node, std::string file, std::string prefix)
      : node_(node), file_(std::move(file)), prefix_(std::move(prefix)) {
    if (node_.IsNull()) return;  // "section:" with nothing under it
    if (!node_.IsMap()) fail(node_, "", "expected a mapping of keys");
  }

  /// Reads `key` into `out` if present (keeps `out` otherwise). Returns true if it was present.
  template <typename T>
  bool read(const std::string& key, T& out) {
    known_.insert(key);
    const std::optional<YAML::Node> found = find(key);
    if (!found) return false;
    const YAML::Node& value = *found;
    if (value.IsNull()) fail(find_key(key), key, "has no value: expected " + type_name(out));
    bool ok = IsScalarLike<T>::value ? value.IsScalar() : value.IsSequence();
    if (ok) {
      try {
        out = value.as<T>();
      } catch (const YAML::BadConversion&) {
        ok = false;
      }
    }
    if (!ok) fail(value, key, "expected " + type_name(out));
    return true;
  }

  /// Reads a sub-mapping (null node if absent).
  YAML::Node child(const std::string& key) {
    known_.insert(key);
    return find(key).value_or(YAML::Node{});
  }

  /// A value's problem, named by its key.
  [[noreturn]] void fail(const YAML::Node& where, const std::string& key,
                         const std::string& problem) const {
    throw InputError(file_, line_of(where), field(key), problem);
  }

  std::string field(const std::string& key) const {
    return prefix_.empty() ? key : key.empty() ? prefix_ : prefix_ + "." + key;
  }

  /// A map key as text. YAML allows sequences and maps as keys ("? [a]"); a config never needs
  /// them, and as<std::string>() would throw a YAML exception that escapes as an internal error.
  std::string key_text(const YAML::Node& key) const {
    if (!key.IsScalar()) fail(key, "", "a key must be a plain name, not a list or a map");
    return key.Scalar();
  }

  /// Throws for the first key that no read() or child() asked for.
  void reject_unknown() const {
    if (!node_.IsMap()) return;
    for (const auto& entry : node_) {
      const auto key = key_text(entry.first);
      if (known_.count(key) == 0) fail(entry.first, key, "unknown key");
    }
  }

  /// The value under `key`; an undefined node when absent (a default YAML::Node is a defined null).
  std::optional<YAML::Node> find(const std::string& key) const {
    if (!node_.IsMap()) return std::nullopt;
    for (const auto& entry : node_) {
      if (key_text(entry.first) == key) return entry.second;
    }
    return std::nullopt;
  }

  // The key itself: where an empty value is reported (an empty value has no position of its own).
  YAML::Node find_key(const std::string& key) const {
    for (const auto& entry : node_) {
      if (key_text(entry.first) == key) return entry.first;
    }
    return node_;
  }

 private:
  template <typename T>
  struct IsScalarLike : std::true_type {};
  template <typename U>
  struct IsScalarLike<std::vector<U>> : std::false_type {};

  YAML::Node node_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> known_;
};

// A value read successfully but outside its range.
template <typename T, typename Check>
void read_checked(Section& section, const std::string& key, T& out, Check is_valid,
                  const std::string& expectation) {
  if (section.read(key, out) && !is_valid(out)) {
    section.fail(*section.find(key), key, "expected " + expectation);
  }
}

bool non_negative(double value) {
  return value >= 0.0;
}
bool unit_interval(double value) {
  return value >= 0.0 && value <= 1.0;
}

void read_source(Section section, SourceConfig& source) {
  section.read("uri", source.uri);
  read_checked(
      section, "width", source.width, [](int v) { return v >= 0; }, "a size >= 0");
  read_checked(
      section, "height", source.height, [](int v) { return v >= 0; }, "a size >= 0");
  read_checked(section, "fps", source.fps, non_negative, "a rate >= 0");
  section.reject_unknown();
}

void read_playback(Section section, PlaybackConfig& playback) {
  std::string mode;
  if (section.read("mode", mode)) {
    const auto parsed = pipeline::parse_playback_mode(mode);
    if (!parsed) {
      section.fail(*section.find("mode"), "mode", "expected " + pipeline::playback_mode_alternatives());
    }
    playback.mode = *parsed;
  }
  read_checked(
      section, "latency_ms", playback.latency_ms, [](double v) { return v > 0.0; },
      "a latency > 0");
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
  read_checked(
      section, "threads", detector.threads, [](int v) { return v >= 0; }, "a count >= 0");
  read_checked(section, "score_threshold", detector.score_threshold, unit_interval,
               "a score in [0, 1]");
  read_checked(section, "nms_threshold", detector.nms_threshold, unit_interval, "an IoU in [0, 1]");
  read_checked(
      section, "classes", detector.classes,
      [](const std::vector<int>& ids) {
        for (const int id : ids) {
          if (id < 0) return false;
        }
        return true;
      },
      "class ids >= 0");
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
  section.read("udp", output.udp);
  section.read("binary_file", output.binary_file);
  section.read("jsonl_file", output.jsonl_file);
  section.read("video_file", output.video_file);
  section.read("report_file", output.report_file);
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
  read_checked(top, "stats_interval_s", config.stats_interval_s, non_negative, "an interval >= 0");
  top.read("stream_id", config.stream_id);
  read_checked(
      top, "max_frames", config.max_frames, [](std::int64_t v) { return v >= 0; }, "a count >= 0");
  top.reject_unknown();
  return config;
}

RunConfig load_run_config(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path, 0, "", "cannot open the configuration file");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_run_config(text.str(), path);
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
