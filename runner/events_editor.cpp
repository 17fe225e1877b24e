#include "runner/events_editor.hpp"

#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/output_file.hpp"
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

EventsEditor::EventsEditor(std::vector<Source> sources, outputs::EventMetrics& metrics,
                           std::string config_file, bool listed)
    : sources_(std::move(sources)),
      metrics_(metrics),
      config_file_(std::move(config_file)),
      listed_(listed) {}

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
  config.frame_period_seconds = source.frame_period_seconds;

  const std::lock_guard<std::mutex> lock(saving_);
  // The file first: a save that cannot be kept changes nothing.
  std::string saved;
  if (!config_file_.empty()) {
    try {
      YAML::Node file = YAML::Load(read_text_file(config_file_));
      YAML::Node place = listed_ ? file["sources"][index] : file["source"];
      place["events"] = node;
      YAML::Emitter out;
      out << file;
      out << YAML::Newline;
      OutputFile written(config_file_, OutputFile::Publish::on_close);
      written.write(std::string_view(out.c_str(), out.size()));
      written.close();
      saved = config_file_;
    } catch (const std::exception& error) {
      return {500,
              {{"error", "not applied: the configuration file cannot be written: " +
                             std::string(error.what())}},
              nullptr};
    }
  }
  outputs::EventMetrics::Source names{source.stream_id, {}, {}};
  for (const auto& line : config.lines) names.lines.push_back(line.name);
  for (const auto& zone : config.zones) names.zones.push_back(zone.name);
  nlohmann::json geometry =
      web_geometry(config, source.stream_id, source.uri, source.width, source.height);
  const std::uint32_t generation = ++generation_;
  // The names first: the sink knows them before the first message counted with them.
  metrics_.post(std::move(names), generation);
  source.mailbox->post(config, generation);
  spdlog::info(
      "web: stream {}: {} line(s) and {} zone(s) saved (configuration {}), counted from "
      "zero{}",
      source.stream_id, config.lines.size(), config.zones.size(), generation,
      saved.empty() ? " (not written to a file: the run has no --config)"
                    : ", written to " + saved);
  return {200,
          {{"generation", generation},
           {"saved_to", saved},
           {"counts", "restart from zero for this source's lines and zones"}},
          std::move(geometry)};
}

}  // namespace rtmot::runner
