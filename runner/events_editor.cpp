#include "runner/events_editor.hpp"

#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include "common/input_error.hpp"
#include "events/events_equal.hpp"
#include "events/events_yaml.hpp"
#include "runner/web_geometry.hpp"

namespace rtmot::runner {
namespace {

constexpr const char* kRequest = "request";

outputs::SaveAnswer refused(const InputError& error) {
  return {400,
          {{"error", error.what()},
           {"field", error.field()},
           {"line", error.line()},
           {"problem", error.problem()}},
          nullptr};
}

}  // namespace

EventsEditor::EventsEditor(std::vector<Source> sources, outputs::EventMetrics* metrics,
                           ConfigDocument& document, bool listed)
    : sources_(std::move(sources)), metrics_(metrics), document_(document), listed_(listed) {}

outputs::SaveAnswer EventsEditor::save(std::size_t index, const std::string& body) {
  if (index >= sources_.size()) {
    return {404, {{"error", "no source " + std::to_string(index)}}, nullptr};
  }
  const Source& source = sources_[index];
  const std::string field =
      listed_ ? "sources[" + std::to_string(index) + "].events" : "source.events";
  YAML::Node node;
  events::EventsConfig config;
  try {
    try {
      node = YAML::Load(body);
    } catch (const YAML::Exception& error) {
      throw InputError(kRequest, error.mark.line + 1, field, error.msg);
    }
    const events::EventsSpec spec = events::read_events_spec(node, kRequest, field);
    config = events::resolve_events(spec, source.width, source.height);
  } catch (const InputError& error) {
    return refused(error);
  }
  config.frame_period_seconds = source.running.frame_period_seconds;

  const std::lock_guard<std::mutex> lock(saving_);
  // The file first: a save that cannot be kept changes nothing.
  try {
    document_.save([&](YAML::Node& file) {
      YAML::Node place = listed_ ? file["sources"][index] : file["source"];
      place["events"] = node;
    });
  } catch (const std::exception& error) {
    return {500,
            {{"error", "not applied: the configuration file cannot be written: " +
                           std::string(error.what())}},
            nullptr};
  }
  const std::string& saved = document_.target();
  nlohmann::json geometry =
      web_geometry(config, source.stream_id, source.uri, source.width, source.height);
  const std::size_t lines = config.lines.size();
  const std::size_t zones = config.zones.size();
  const std::uint32_t generation = hand_over(index, std::move(config));
  spdlog::info(
      "web: stream {}: {} line(s) and {} zone(s) saved (configuration {}), counted from "
      "zero{}",
      source.stream_id, lines, zones, generation,
      saved.empty() ? " (not written to a file: the run has no --config)"
                    : ", written to " + saved);
  return {200,
          {{"generation", generation},
           {"saved_to", saved},
           {"counts", "restart from zero for this source's lines and zones"}},
          std::move(geometry)};
}

bool EventsEditor::apply(std::size_t index, events::EventsConfig config, const std::string& why) {
  const std::lock_guard<std::mutex> lock(saving_);
  Source& source = sources_.at(index);
  config.frame_period_seconds = source.running.frame_period_seconds;
  if (events::same_events(config, source.running)) return false;
  const std::size_t lines = config.lines.size();
  const std::size_t zones = config.zones.size();
  const std::uint32_t generation = hand_over(index, std::move(config));
  spdlog::info("{}: stream {}: {} line(s) and {} zone(s) (configuration {}), counted from zero",
               why, source.stream_id, lines, zones, generation);
  return true;
}

nlohmann::json EventsEditor::geometry() const {
  const std::lock_guard<std::mutex> lock(saving_);
  nlohmann::json all = nlohmann::json::array();
  for (const Source& source : sources_) {
    all.push_back(
        web_geometry(source.running, source.stream_id, source.uri, source.width, source.height));
  }
  return all;
}

std::uint32_t EventsEditor::hand_over(std::size_t index, events::EventsConfig config) {
  Source& source = sources_[index];
  const std::uint32_t generation = ++generation_;
  if (metrics_ != nullptr) {
    outputs::EventMetrics::Source names{source.stream_id, {}, {}};
    for (const auto& line : config.lines) names.lines.push_back(line.name);
    for (const auto& zone : config.zones) names.zones.push_back(zone.name);
    // The names first: the sink knows them before the first message counted with them.
    metrics_->post(std::move(names), generation);
  }
  source.running = config;
  if (source.video_mailbox != nullptr) source.video_mailbox->post(config, generation);
  source.mailbox->post(std::move(config), generation);
  return generation;
}

}  // namespace rtmot::runner
