#include "runner/run_config.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/input_path.hpp"
#include "common/nearest_name.hpp"
#include "common/yaml_section.hpp"
#include "platform/video_uri.hpp"
#include "runner/run_settings.hpp"
#include "runner/sequence_clock_source.hpp"
#include "runner/yaml_document.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker_options.hpp"

namespace rtmot::runner {
namespace {

// A configuration is a page of text: a bigger file is not one.
constexpr std::uint64_t kMaxConfigBytes = 1 << 20;

// Keys whose value is a structure of its own, read by its own strict reader: the source's events
// (lines and zones, events/events_yaml.hpp).
using StructuredReader = void (*)(const YAML::Node& value, const Section& where,
                                  const std::string& name, RunConfig& config);
const std::map<std::string, StructuredReader>& structured_keys() {
  static const std::map<std::string, StructuredReader> readers = {
      {"source.events",
       [](const YAML::Node& value, const Section& where, const std::string& name,
          RunConfig& config) {
         config.source.events = events::read_events_spec(value, where.file(), where.field(name));
       }},
  };
  return readers;
}

bool has_settings_under(const std::string& prefix) {
  const std::string start = prefix + ".";
  for (const auto& setting : run_settings()) {
    if (setting.key.compare(0, start.size(), start) == 0) return true;
  }
  return false;
}

// The names a mapping at `prefix` ("" for the top, "detector", ...) may hold: its settings, its
// structured keys, its sub-mappings and `read_elsewhere`; for "did you mean" (common/nearest_name).
std::vector<std::string> names_under(const std::string& prefix,
                                     const std::set<std::string>& read_elsewhere) {
  const std::string start = prefix.empty() ? "" : prefix + ".";
  std::set<std::string> names(read_elsewhere.begin(), read_elsewhere.end());
  const auto add = [&](const std::string& key) {
    if (key.compare(0, start.size(), start) != 0) return;
    names.insert(key.substr(start.size(), key.find('.', start.size()) - start.size()));
  };
  for (const auto& setting : run_settings()) add(setting.key);
  for (const auto& entry : structured_keys()) add(entry.first);
  return {names.begin(), names.end()};
}

// The value of a setting as text, as the command line gives it: a scalar, or a list joined with
// commas (an empty list is "all").
std::string value_text(const Section& section, const YAML::Node& key, const YAML::Node& value,
                       const RunSetting& setting, const std::string& name) {
  const std::string expected = "expected " + setting.expected;
  if (value.IsNull()) section.fail(key, name, "has no value: " + expected);
  if (!setting.list) {
    if (!value.IsScalar()) section.fail(value, name, expected);
    return value.Scalar();
  }
  if (!value.IsSequence()) section.fail(value, name, "expected a list: " + setting.expected);
  if (value.size() == 0) return "all";
  std::string text;
  for (const auto& item : value) {
    if (!item.IsScalar()) section.fail(item, name, expected);
    text += (text.empty() ? "" : ",") + item.Scalar();
  }
  return text;
}

// One mapping of the file: every key is a setting of the table under `prefix` (its YAML path) or
// a mapping of more of them. Errors name the field as `section` does (sources[1].width).
void read_settings(const Section& section, const YAML::Node& node, const std::string& prefix,
                   RunConfig& config, const std::set<std::string>& read_elsewhere = {}) {
  if (!node.IsMap()) return;  // null: "section:" with nothing under it (Section checked the rest)
  for (const auto& entry : node) {
    const std::string name = section.key_text(entry.first);
    if (read_elsewhere.count(name) > 0) continue;
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (const auto structured = structured_keys().find(key);
        structured != structured_keys().end()) {
      structured->second(entry.second, section, name, config);
    } else if (const RunSetting* setting = find_run_setting(key)) {
      const std::string text = value_text(section, entry.first, entry.second, *setting, name);
      std::string problem;
      if (!setting->set(config, text, problem)) {
        section.fail(entry.second, name, refusal(*setting, text, problem));
      }
      config.lines[section.field(name)] = line_of(entry.second);
    } else if (has_settings_under(key)) {
      const Section child(entry.second, section.file(), section.field(name));
      read_settings(child, entry.second, key, config);
    } else {
      section.fail(entry.first, name,
                   "unknown key" + did_you_mean(name, names_under(prefix, read_elsewhere)));
    }
  }
}

// `sources:` a list whose entries are a URI or a mapping with the keys of `source`.
void read_sources(const Section& top, const YAML::Node& list, RunConfig& config) {
  if (list.IsNull()) return;
  if (!list.IsSequence()) top.fail(list, "sources", "expected a list of sources");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node entry = list[i];
    const std::string field = "sources[" + std::to_string(i) + "]";
    RunConfig scratch;  // the source settings of the table, applied to its `source`
    if (entry.IsScalar()) {
      scratch.source.uri = entry.Scalar();
    } else {
      read_settings(Section(entry, top.file(), field), entry, "source", scratch);
    }
    if (scratch.source.uri.empty()) {
      throw InputError(top.file(), line_of(entry), field, "no uri given");
    }
    config.sources.push_back(scratch.source);
  }
  if (config.sources.empty()) top.fail(list, "sources", "the list is empty");
}

void read_tracker(Section section, tracker::TrackerConfig& config) {
  // Without a preset the pipeline starts from the default (best measured) one, as `rtmot track`.
  std::string preset{tracker::default_preset_name()};
  section.read("preset", preset);
  if (!apply_preset(preset, config)) {
    section.fail(*section.find("preset"), "preset", "expected one of: " + tracker::preset_names());
  }
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

}  // namespace

bool apply_preset(std::string_view name, tracker::TrackerConfig& config) {
  const auto found = tracker::find_preset(std::string(name));
  if (!found) return false;
  // No preset assumes a score scale (the default's cut is relative to the stream's own scores), so
  // a preset applies the same everywhere; the detector's score_threshold is the detector's own
  // cut, made before the tracker sees anything.
  config = *found;
  config.frame_rate = 0.0;  // from the source (or seqinfo.ini) unless set after the preset
  config.image_width = 0.F;
  config.image_height = 0.F;
  return true;
}

RunConfig parse_run_config(const std::string& yaml_text, const std::string& file_name) {
  const YAML::Node root = load_one_document(yaml_text, file_name);
  RunConfig config;
  config.file = file_name;
  apply_preset(tracker::default_preset_name(), config.tracker);

  const Section top(root, file_name, "");
  // `tracker:` has its own table; `sources:` is a list of `source:` mappings; every other key is a
  // setting of runner/run_settings.hpp, or a mapping of them.
  read_settings(top, root, "", config, {"tracker", "sources"});
  if (const auto tracker = top.find("tracker")) {
    read_tracker(Section(*tracker, file_name, "tracker"), config.tracker);
  }
  if (const auto sources = top.find("sources")) read_sources(top, *sources, config);
  if (!config.sources.empty() && !config.source.uri.empty()) {
    top.fail(*top.find("sources"), "sources", "give either source.uri or sources, not both");
  }
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
  config.loaded_from = found;
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

namespace {

// A camera or stream (a malformed URI is reported when the source opens).
bool is_live_uri(const std::string& uri) {
  try {
    return platform::is_live(platform::parse_video_uri(uri));
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

std::optional<std::string> flip_problem(const SourceConfig& source) {
  if (source.flip == platform::Orientation::none || !is_sequence_uri(source.uri)) {
    return std::nullopt;
  }
  return "a mot-seq:// source has no frames to turn: its boxes are the det file's, as the "
         "sequence was recorded ('" +
         source.uri + "')";
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
  if (!config.output.web_save_to.empty() && config.loaded_from.empty()) {
    missing("output.web_save_to",
            "needs --config: the file saved is a copy of the configuration file with the change");
  }
  if (sources.size() > 1 && config.output.video) {
    missing("output.video_file", "the annotated video needs a single source");
  }
  if (config.detector.kind == DetectorKind::ssd && config.detector.model.empty()) {
    missing("detector.model", "the ssd detector needs a model file");
  }
  if (config.output.mot_detections && config.output.mot_results.empty()) {
    missing("output.mot_detections", "writes into the results folder: set output.mot_results");
  }
  if (config.detector.kind == DetectorKind::replay && config.detector.det_file.empty()) {
    missing("detector.det_file", "the replay detector needs a det.txt file");
  }
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const SourceConfig& source = sources[i];
    // A live camera or stream does not end, and a mot-seq:// sequence is scored frame by frame:
    // looping is for files (and images://, test://).
    if (source.loop != 0 && (is_sequence_uri(source.uri) || is_live_uri(source.uri))) {
      missing(config.sources.empty() ? "source.loop" : "sources[" + std::to_string(i) + "].loop",
              "loops a file, not '" + source.uri + "' (a live source or a mot-seq:// sequence)");
    }
  }
  for (std::size_t i = 0; i < sources.size(); ++i) {
    if (const auto problem = flip_problem(sources[i])) {
      missing(config.sources.empty() ? "source.flip" : "sources[" + std::to_string(i) + "].flip",
              *problem);
    }
  }
  for (const SourceConfig& source : sources) {
    if (!is_sequence_uri(source.uri)) continue;
    if (config.detector.kind == DetectorKind::ssd) {
      missing("detector.kind", "a mot-seq:// source has no images: use the replay detector");
    }
    if (config.output.video) {
      missing("output.video_file", "a mot-seq:// source has no images to annotate");
    }
  }
}

void check_model_found(const RunConfig& config) {
  if (config.detector.kind == DetectorKind::ssd) {
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
