#include "detector/model_description.hpp"

#include <yaml-cpp/yaml.h>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/yaml_section.hpp"

namespace rtmot::detector {
namespace {

constexpr std::uint64_t kMaxDescriptionBytes = 64 << 10;

template <typename Enum, typename Names>
void read_enum(Section& section, const std::string& key, const Names& names, Enum& out) {
  std::string text;
  if (!section.read(key, text)) return;
  const auto value = names.parse(text);
  if (!value) {
    section.fail(*section.find(key), key, "'" + text + "': expected " + names.alternatives());
  }
  out = *value;
}

ModelDescription parse(const std::filesystem::path& path, const std::string& text) {
  const std::string file = path.string();
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? 0 : e.mark.line + 1, "", "not valid YAML: " + e.msg);
  }
  ModelDescription description;
  description.file = path;
  Section top(root, file, "");
  read_enum(top, "layout", kOutputLayoutNames, description.layout);
  if (description.layout == OutputLayout::decoded) {
    description.box_output = "boxes";
    description.score_output = "scores";
  }
  Section input(top.child("input"), file, "input");
  read_checked(input, "size", description.input_size, within(kModelInputSize, kModelInputSize),
               std::to_string(kModelInputSize) + " (the only input size the detector feeds yet)");
  read_enum(input, "colour", kColourOrderNames, description.colour);
  read_checked(input, "mean", description.mean, within(-255.0, 255.0), "a number in -255..255");
  read_checked(
      input, "scale", description.scale, [](double v) { return v > 0.0 && v <= 1.0; },
      "a number above 0 and at most 1");
  input.reject_unknown();
  Section outputs(top.child("outputs"), file, "outputs");
  outputs.read("boxes", description.box_output);
  outputs.read("scores", description.score_output);
  outputs.reject_unknown();
  std::string labels;
  if (top.read("labels", labels)) {
    if (labels.empty()) top.fail(*top.find("labels"), "labels", "names no file");
    description.labels = std::filesystem::path(labels).is_absolute() ? std::filesystem::path(labels)
                                                                     : path.parent_path() / labels;
  }
  top.reject_unknown();
  return description;
}

}  // namespace

std::filesystem::path description_path_of(const std::filesystem::path& model_path) {
  std::filesystem::path path = model_path;
  return path.replace_extension(".model.yaml");
}

ModelDescription read_model_description(const std::filesystem::path& model_path) {
  const std::filesystem::path path = description_path_of(model_path);
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, error))) return {};
  try {
    return parse(path, read_text_file(path, kMaxDescriptionBytes));
  } catch (const InputError& e) {
    // The model's files are the model's exit code, whichever reader found the problem.
    throw InputError(e.file(), e.line(), e.field(), e.problem(), ExitCode::bad_model);
  }
}

}  // namespace rtmot::detector
