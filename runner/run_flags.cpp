#include "runner/run_flags.hpp"

#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "runner/run_settings.hpp"
#include "tracker/presets.hpp"

namespace rtmot::runner {

void RunFlags::add_to(CLI::App& cli) {
  preset_given_ = cli.add_option(
      "--preset", preset_,
      "tracker preset, replacing the file's tracker section: " + tracker::preset_names());
  cli.add_option("--source", sources_,
                 "source URI: file path, v4l2:///dev/videoN, csi://N, rtsp://..., test://..., "
                 "mot-seq://SEQUENCE_DIR; repeat for several sources (one batched detector)")
      ->allow_extra_args(false);  // one URI per --source
  const auto& settings = run_settings();
  // Sized once: CLI11 keeps a reference to each string.
  values_.assign(settings.size(), std::string{});
  given_.assign(settings.size(), nullptr);
  for (std::size_t i = 0; i < settings.size(); ++i) {
    const RunSetting& setting = settings[i];
    if (setting.flag.empty()) continue;
    given_[i] = cli.add_option(setting.flag, values_[i],
                               setting.doc + " (" + setting.key + ": " + setting.expected + ")");
  }
  tracker_flags_.add_to(cli);
}

void RunFlags::apply(RunConfig& config) const {
  const auto refuse = [](const std::string& flag, const std::string& problem) {
    throw InputError("command line", 0, flag, problem, ExitCode::usage);
  };
  if (preset_given_ != nullptr && preset_given_->count() > 0 &&
      !apply_preset(preset_, config.tracker)) {
    refuse("--preset", "'" + preset_ + "': expected one of: " + tracker::preset_names());
  }
  if (!sources_.empty()) {
    // Replaces the file's source(s); each keeps the file's `source` capture settings.
    SourceConfig settings = config.source;
    settings.stream_id = -1;
    config.sources.clear();
    for (const std::string& uri : sources_) {
      settings.uri = uri;
      config.sources.push_back(settings);
    }
    config.source = config.sources.front();
    if (config.sources.size() == 1) {
      config.sources.clear();
    } else {
      config.source.uri.clear();
    }
  }
  const auto& settings = run_settings();
  for (std::size_t i = 0; i < settings.size(); ++i) {
    if (given_[i] == nullptr || given_[i]->count() == 0) continue;
    std::string problem;
    if (!settings[i].set(config, values_[i], problem)) {
      refuse(settings[i].flag, refusal(settings[i], values_[i], problem));
    }
    config.lines.erase(settings[i].key);  // the file's line no longer holds the value
    // A source's flag (--input-flip, ...) is for every source of the run: the file's `sources:`
    // or several --source, which were copied from `source` above.
    if (settings[i].key.rfind("source.", 0) == 0) {
      for (SourceConfig& source : config.sources) {
        RunConfig scratch;
        scratch.source = source;
        settings[i].set(scratch, values_[i], problem);
        source = scratch.source;
      }
    }
    if (settings[i].key == "source.flip") {
      for (const SourceConfig& source : source_list(config)) {
        if (const auto problem = flip_problem(source)) refuse(settings[i].flag, *problem);
      }
    }
    // --model names the SSD's model: it means the SSD, whatever the file's detector.kind.
    if (settings[i].key == "detector.model") config.detector.kind = DetectorKind::ssd;
    // --det-file names replayed detections: it means the replay detector, the same way.
    if (settings[i].key == "detector.det_file") config.detector.kind = DetectorKind::replay;
  }
  tracker_flags_.apply(config.tracker);
}

}  // namespace rtmot::runner
