#pragma once
// SIGHUP: `rtmot run --config FILE` re-reads FILE (docs/web.md, "SIGHUP"). The file is read and
// checked whole by the reader of the start (load_run_config, the command line's flags applied over
// it again, validate, each source's events resolved against its frame); on any error the running
// configuration is kept and one line names file, line and field. Applied live: each source's
// events section (through runner/events_editor.hpp, as a page save: counts from zero under a new
// generation; a section that resolves to the running one keeps its counts) and the detector's
// score cut (runner/settings_editor.hpp). Every other setting that differs from the file the run
// started with is named in one "needs a restart" line and not applied.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "runner/config_document.hpp"
#include "runner/events_editor.hpp"
#include "runner/run_config.hpp"
#include "runner/run_flags.hpp"
#include "runner/settings_editor.hpp"

namespace rtmot::runner {

/// The settings of `before` and `after` (YAML documents of run configurations) that differ, as
/// dotted paths ("detector.model", "sources[1].uri"), leaving out those a run takes live (every
/// source's `events`, `detector.score_threshold`). A key present in one only is named whole.
std::vector<std::string> settings_needing_restart(const YAML::Node& before,
                                                  const YAML::Node& after);

class ConfigReloader {
 public:
  /// `config_file`: the run's --config ("": a reload has nothing to re-read); `flags`: the
  /// command line's, applied over the file as at start. Pointers not owned, outliving this.
  ConfigReloader(std::string config_file, const RunFlags& flags, EventsEditor& events,
                 SettingsEditor& settings, pipeline::ScoreCut& score_cut, ConfigDocument& document);

  /// A non-pipeline thread, one at a time: re-reads the file and applies what it can (above).
  void reload();

 private:
  const std::string config_file_;
  const RunFlags& flags_;
  EventsEditor& events_;
  SettingsEditor& settings_;
  pipeline::ScoreCut& score_cut_;
  ConfigDocument& document_;
  YAML::Node started_with_;  // the file as the run started (its settings are the running ones)
};

}  // namespace rtmot::runner
