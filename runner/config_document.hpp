#pragma once
// The running configuration's text, where the page's saves go (docs/web.md): the `--config` file as
// read at start or at the last SIGHUP that was applied, with the saves made since. A save writes
// the whole document, changed, to output.web_save_to when set, else back to the --config file: to a
// temporary beside it, renamed over it once whole (common/output_file.hpp), so a crash leaves the
// old file or the new one. yaml-cpp re-emits it: comments and key order are not kept.
#include <yaml-cpp/yaml.h>

#include <functional>
#include <mutex>
#include <string>

namespace rtmot::runner {

class ConfigDocument {
 public:
  /// `config_file`: the run's --config ("" for none: nothing is ever written); `save_to`:
  /// output.web_save_to ("" = `config_file`). Reads `config_file` now.
  ConfigDocument(std::string config_file, std::string save_to);

  /// Where saves are written ("" = nowhere).
  const std::string& target() const { return target_; }

  /// Any thread (serialised): applies `change` to a copy of the document and writes the copy to
  /// target(); the copy becomes the document once written. Throws (std::exception) when it cannot
  /// be written, and the document is unchanged. Without a target: nothing happens.
  void save(const std::function<void(YAML::Node& document)>& change);

  /// After a SIGHUP re-read `config_file` and applied it: the document is the file's.
  void replace(const YAML::Node& document);

 private:
  std::mutex mutex_;
  std::string target_;
  YAML::Node document_;  // guarded by mutex_
};

}  // namespace rtmot::runner
