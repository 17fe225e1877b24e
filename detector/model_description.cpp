#include "detector/model_description.hpp"

#include <yaml-cpp/yaml.h>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/yaml_section.hpp"
#include "detector/onnx_metadata.hpp"

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

// `path` is the file the YAML came from; `file` how errors name it; relative labels paths are
// relative to `path`'s folder, which is the model's either way.
ModelDescription parse(const std::filesystem::path& path, const std::string& file,
                       const std::string& text) {
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
  read_checked(input, "size", description.input_size,
               within(kMinModelInputSize, kMaxModelInputSize),
               "a whole number in " + std::to_string(kMinModelInputSize) + ".." +
                   std::to_string(kMaxModelInputSize) + " (pixels of the square input)");
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

std::string described_by(const ModelDescription& description) {
  if (description.file.empty()) return "the bundled contract";
  return description.inside_model
             ? description.file.string() + " (its metadata " + kDescriptionMetadataKey + ")"
             : description.file.string();
}

ModelDescription read_model_description(const std::filesystem::path& model_path) {
  const std::filesystem::path path = description_path_of(model_path);
  std::error_code error;
  const bool beside = std::filesystem::exists(std::filesystem::symlink_status(path, error));
  try {
    if (beside) return parse(path, path.string(), read_text_file(path, kMaxDescriptionBytes));
    const std::optional<std::string> inside =
        onnx_metadata_value(model_path, kDescriptionMetadataKey, kMaxDescriptionBytes);
    if (!inside) return {};
    ModelDescription description = parse(
        model_path, model_path.string() + " (metadata " + kDescriptionMetadataKey + ")", *inside);
    description.inside_model = true;
    return description;
  } catch (const InputError& e) {
    // The model's files are the model's exit code, whichever reader found the problem.
    throw InputError(e.file(), e.line(), e.field(), e.problem(), ExitCode::bad_model);
  }
}

}  // namespace rtmot::detector
