#include "runner/class_choice.hpp"

#include <fmt/format.h>

#include "common/checked_number.hpp"
#include "common/input_error.hpp"
#include "detector/model_description.hpp"

namespace rtmot::runner {

std::shared_ptr<const detector::LabelTable> run_labels(const RunConfig& config) {
  if (config.detector.kind != DetectorKind::ssd || config.detector.model.empty()) {
    return std::make_shared<const detector::LabelTable>(detector::LabelTable::coco());
  }
  const detector::ModelDescription description =
      detector::read_model_description(config.detector.model);
  return std::make_shared<const detector::LabelTable>(
      description.labels.empty() ? detector::LabelTable::coco()
                                 : detector::LabelTable::from_file(description.labels));
}

std::vector<int> resolve_classes(const RunConfig& config, const detector::LabelTable& labels) {
  std::vector<int> ids;
  for (const std::string& word : config.detector.classes) {
    int id = labels.id_of(word);
    if (id < 0) {
      const auto number = parse_integer(word, {1, labels.columns() - 1});
      if (number && !labels.name(static_cast<int>(*number)).empty()) {
        id = static_cast<int>(*number);
      }
    }
    if (id < 0) {
      const auto line = config.lines.find("detector.classes");
      throw InputError(config.file, line == config.lines.end() ? 0 : line->second,
                       "detector.classes",
                       fmt::format("'{}' is not a class of the model's labels ({}): expected a "
                                   "name, or the number of a named column 1..{}",
                                   word, labels.source(), labels.columns() - 1),
                       ExitCode::usage);
    }
    ids.push_back(id);
  }
  return ids;
}

void check_classes(const RunConfig& config) {
  if (config.detector.kind != DetectorKind::ssd) return;
  resolve_classes(config, *run_labels(config));
}

}  // namespace rtmot::runner
