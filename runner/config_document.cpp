#include "runner/config_document.hpp"

#include <string_view>

#include "common/input_file.hpp"
#include "common/output_file.hpp"

namespace rtmot::runner {

ConfigDocument::ConfigDocument(std::string config_file, std::string save_to)
    : target_(!save_to.empty() ? std::move(save_to) : config_file) {
  if (!config_file.empty()) document_ = YAML::Load(read_text_file(config_file));
}

void ConfigDocument::save(const std::function<void(YAML::Node& document)>& change) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (target_.empty()) return;
  // A deep copy: a YAML::Node copied by value shares its data.
  YAML::Node changed = YAML::Clone(document_);
  change(changed);
  YAML::Emitter out;
  out << changed;
  out << YAML::Newline;
  OutputFile written(target_, OutputFile::Publish::on_close);
  written.write(std::string_view(out.c_str(), out.size()));
  written.close();
  document_ = changed;
}

void ConfigDocument::replace(const YAML::Node& document) {
  const std::lock_guard<std::mutex> lock(mutex_);
  document_ = YAML::Clone(document);
}

}  // namespace rtmot::runner
