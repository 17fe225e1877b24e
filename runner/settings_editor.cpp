#include "runner/settings_editor.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "runner/run_settings.hpp"
#include "tracker/tracker_options.hpp"

namespace rtmot::runner {
namespace {

constexpr const char* kScoreKey = "score_threshold";
constexpr const char* kScoreSetting = "detector.score_threshold";

outputs::SaveAnswer refused(const std::string& field, const std::string& problem) {
  return {400,
          {{"error", fmt::format("request: {}: {}", field, problem)},
           {"field", field},
           {"problem", problem}},
          nullptr};
}

// A key of the configuration file (bare, as "nms_threshold", or whole, as
// "detector.nms_threshold").
// As typed (0.6), not as the float's nearest double shows it (0.6000000238418579).
double shown(float cut) {
  return std::round(static_cast<double>(cut) * 1e6) / 1e6;
}

bool is_setting(const std::string& key) {
  if (find_run_setting(key) != nullptr || find_run_setting("detector." + key) != nullptr)
    return true;
  const std::string bare = key.rfind("tracker.", 0) == 0 ? key.substr(8) : key;
  for (const auto& option : tracker::tracker_options()) {
    if (option.name == bare) return true;
  }
  return false;
}

}  // namespace

SettingsEditor::SettingsEditor(pipeline::ScoreCut& score_cut, ConfigDocument& document)
    : score_cut_(score_cut), document_(document) {}

std::optional<std::string> SettingsEditor::score_problem(float cut) const {
  if (!(cut > 0.F)) return std::string("expected a number in (0, 1]");
  if (cut < score_cut_.floor()) {
    return fmt::format(
        "{} is below the cut the detector was started with ({}): lowering it needs a restart", cut,
        score_cut_.floor());
  }
  return std::nullopt;
}

nlohmann::json SettingsEditor::current() const {
  return {{kScoreKey, shown(score_cut_.get())}};
}

outputs::SaveAnswer SettingsEditor::save(const std::string& body) {
  YAML::Node node;
  try {
    node = YAML::Load(body);
  } catch (const YAML::Exception& error) {
    return refused("settings", "line " + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
  if (!node.IsMap() || node.size() == 0) {
    return refused("settings", "expected an object such as {\"score_threshold\": 0.4}");
  }
  std::optional<float> score;
  std::string score_text;
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (key != kScoreKey) {
      return refused(key, is_setting(key)
                              ? "needs a restart: change it in the configuration file and restart"
                              : "unknown setting (settable here: score_threshold)");
    }
    const RunSetting& setting = *find_run_setting(kScoreSetting);
    RunConfig scratch;
    std::string problem;
    score_text = entry.second.IsScalar() ? entry.second.Scalar() : std::string();
    if (!entry.second.IsScalar() || !setting.set(scratch, score_text, problem)) {
      return refused(kScoreKey, refusal(setting, score_text, problem));
    }
    if (const auto why = score_problem(scratch.detector.score_threshold)) {
      return refused(kScoreKey, *why);
    }
    score = scratch.detector.score_threshold;
  }
  try {
    document_.save([&](YAML::Node& file) { file["detector"][kScoreKey] = score_text; });
  } catch (const std::exception& error) {
    return {500,
            {{"error", "not applied: the configuration file cannot be written: " +
                           std::string(error.what())}},
            nullptr};
  }
  score_cut_.set(*score);
  const std::string& saved = document_.target();
  spdlog::info("web: the detector's score cut is {} from the next frame on{}", *score,
               saved.empty() ? " (not written to a file: the run has no --config)"
                             : ", written to " + saved);
  return {200, {{kScoreKey, shown(*score)}, {"saved_to", saved}}, nullptr};
}

}  // namespace rtmot::runner
