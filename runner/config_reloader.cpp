#include "runner/config_reloader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <optional>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "events/events_yaml.hpp"

namespace rtmot::runner {
namespace {

bool taken_live(const std::string& path) {
  if (path == "detector.score_threshold" || path == "source.events") return true;
  // sources[N].events
  return path.rfind("sources[", 0) == 0 && path.size() > 7 &&
         path.compare(path.size() - 7, 7, ".events") == 0 && path.find('.') == path.size() - 7;
}

void differences(const YAML::Node& before, const YAML::Node& after, const std::string& path,
                 std::vector<std::string>& out) {
  if (taken_live(path)) return;
  const std::string named = path.empty() ? "(the whole file)" : path;
  if (!before.IsDefined() || !after.IsDefined() || before.Type() != after.Type()) {
    if (before.IsDefined() != after.IsDefined() || before.Type() != after.Type())
      out.push_back(named);
    return;
  }
  if (before.IsScalar()) {
    if (before.Scalar() != after.Scalar()) out.push_back(named);
    return;
  }
  if (before.IsSequence()) {
    const std::size_t n = std::max(before.size(), after.size());
    for (std::size_t i = 0; i < n; ++i) {
      const std::string item = path + "[" + std::to_string(i) + "]";
      if (i >= before.size() || i >= after.size()) {
        out.push_back(item);
      } else {
        differences(before[i], after[i], item, out);
      }
    }
    return;
  }
  if (before.IsMap()) {
    const auto prefix = path.empty() ? std::string() : path + ".";
    for (const auto& entry : before) {
      const std::string key = entry.first.Scalar();
      differences(entry.second, after[key], prefix + key, out);
    }
    for (const auto& entry : after) {
      const std::string key = entry.first.Scalar();
      if (!before[key].IsDefined())
        differences(YAML::Node(YAML::NodeType::Undefined), entry.second, prefix + key, out);
    }
  }
}

}  // namespace

std::vector<std::string> settings_needing_restart(const YAML::Node& before,
                                                  const YAML::Node& after) {
  std::vector<std::string> out;
  differences(before, after, "", out);
  return out;
}

ConfigReloader::ConfigReloader(std::string config_file, const RunFlags& flags, EventsEditor& events,
                               SettingsEditor& settings, pipeline::ScoreCut& score_cut,
                               ConfigDocument& document)
    : config_file_(std::move(config_file)),
      flags_(flags),
      events_(events),
      settings_(settings),
      score_cut_(score_cut),
      document_(document) {
  if (!config_file_.empty()) started_with_ = YAML::Load(read_text_file(config_file_));
}

void ConfigReloader::reload() {
  if (config_file_.empty()) {
    spdlog::warn("SIGHUP: nothing to re-read (the run has no --config); nothing changed");
    return;
  }
  // Everything is read, checked and resolved before anything is applied.
  YAML::Node document;
  RunConfig fresh;
  std::vector<events::EventsConfig> resolved;
  try {
    // The reader of the start (paths resolved as there), then the document of the same file.
    fresh = load_run_config(config_file_);
    const std::string text = read_text_file(config_file_);
    flags_.apply(fresh);
    validate(fresh);
    document = YAML::Load(text);
    const std::vector<SourceConfig> sources = source_list(fresh);
    if (sources.size() == events_.sources().size()) {
      for (std::size_t i = 0; i < sources.size(); ++i) {
        const auto& running = events_.sources()[i];
        resolved.push_back(
            events::resolve_events(sources[i].events, running.width, running.height));
      }
    }
  } catch (const InputError& error) {
    spdlog::error("SIGHUP: {}; the running configuration is kept", error.what());
    return;
  } catch (const std::exception& error) {
    spdlog::error("SIGHUP: {}: {}; the running configuration is kept", config_file_, error.what());
    return;
  }
  std::vector<std::string> restart = settings_needing_restart(started_with_, document);
  std::vector<std::string> applied;
  const float score = fresh.detector.score_threshold;
  if (score != score_cut_.get()) {
    if (const auto why = settings_.score_problem(score)) {
      restart.push_back("detector.score_threshold (" + *why + ")");
    } else {
      score_cut_.set(score);
      applied.push_back(fmt::format("detector.score_threshold {}", score));
    }
  }
  for (std::size_t i = 0; i < resolved.size(); ++i) {
    if (events_.apply(i, std::move(resolved[i]), "SIGHUP")) {
      applied.push_back(fmt::format("stream {} events", events_.sources()[i].stream_id));
    }
  }
  document_.replace(document);
  if (!restart.empty()) {
    spdlog::warn("SIGHUP: {}: needs a restart: {} (not applied)", config_file_,
                 fmt::join(restart, ", "));
  }
  spdlog::info("SIGHUP: {} re-read: {}", config_file_,
               applied.empty() ? std::string("nothing changed that applies live")
                               : fmt::format("applied {}", fmt::join(applied, ", ")));
}

}  // namespace rtmot::runner
