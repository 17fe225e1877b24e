#pragma once
// A configuration file's one YAML document.
#include <yaml-cpp/yaml.h>

#include <string>

namespace rtmot::runner {

/// The one document of `yaml_text` (read from `file_name`). Throws rtmot::InputError (exit 3)
/// naming the file and line when the text is not YAML, is empty, or holds a second document
/// (yaml-cpp's Load() would read the first and drop the rest silently: settings that never apply).
/// `what` names the file's kind in that message ("a run configuration", "a lines file").
YAML::Node load_one_document(const std::string& yaml_text, const std::string& file_name,
                             const std::string& what = "a run configuration");

}  // namespace rtmot::runner
