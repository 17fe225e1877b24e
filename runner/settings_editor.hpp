#pragma once
// The settings a running `rtmot run` takes without a restart, other than lines and zones
// (runner/events_editor.hpp): the detector's score cut (pipeline/score_cut.hpp), from the page's
// POST /api/settings and from a SIGHUP that re-read the configuration file (docs/web.md).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "outputs/web_server.hpp"
#include "pipeline/score_cut.hpp"
#include "runner/config_document.hpp"

namespace rtmot::runner {

class SettingsEditor {
 public:
  /// Neither is owned; both outlive the editor.
  SettingsEditor(pipeline::ScoreCut& score_cut, ConfigDocument& document);

  /// Any thread: the answer to POST /api/settings (`{"score_threshold": 0.4}`, JSON or YAML).
  /// Checked whole before anything changes: 400 naming the field (a bad value, a setting that
  /// needs a restart, an unknown one); 500 if the file cannot be written (nothing applied).
  outputs::SaveAnswer save(const std::string& body);

  /// Any thread: the settings as they are now, for /api/status.
  nlohmann::json current() const;

  /// Why `cut` cannot be the detector's cut while it runs (below the detector's own, fixed at
  /// start), or nullopt when it can. Range [0, 1] is the reader's (run_settings).
  std::optional<std::string> score_problem(float cut) const;

 private:
  pipeline::ScoreCut& score_cut_;
  ConfigDocument& document_;
};

}  // namespace rtmot::runner
