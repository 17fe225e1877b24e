#pragma once
// New lines and zones for a running source (docs/web.md), from the page's "save" or from a SIGHUP
// that re-read the configuration file. The posted events section (YAML or JSON, as the
// configuration file's `events:`) is read by the file's own reader (events/events_yaml.hpp) and
// resolved against the source's frame; any error is answered with its field and leaves the run as
// it was. A valid one is written into the running configuration's document (runner/
// config_document.hpp: the --config file or output.web_save_to, whole or not at all), then handed
// to the metrics (EventMetrics::post) and to the running pipeline (pipeline/events_mailbox.hpp: the
// track stage counts it from its next frame, from zero, under a new generation).
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "events/events_config.hpp"
#include "outputs/event_metrics.hpp"
#include "outputs/web_server.hpp"
#include "pipeline/events_mailbox.hpp"
#include "runner/config_document.hpp"

namespace rtmot::runner {

class EventsEditor {
 public:
  struct Source {
    std::uint32_t stream_id{0};
    std::string uri;
    int width{0};
    int height{0};
    events::EventsConfig running;  // what the run counts now (resolved, frame period set)
    pipeline::EventsMailbox* mailbox{nullptr};  // not owned
    /// The annotated video's (it draws the lines and zones); not owned, null: none.
    pipeline::EventsMailbox* video_mailbox{nullptr};
  };

  /// `metrics`: null when nothing serves the counts; `document`: where saves are written (not
  /// owned; outlives the editor); `listed`: the file lists its sources under `sources:` (else one
  /// `source:`).
  EventsEditor(std::vector<Source> sources, outputs::EventMetrics* metrics,
               ConfigDocument& document, bool listed);

  /// Any thread (serialised): the answer to POST /api/events?source=N.
  outputs::SaveAnswer save(std::size_t source, const std::string& body);

  /// Any thread (serialised): counts `config` (resolved, as make_inputs resolves a file's) on
  /// source `source` from its next frame, unless it counts the same as the running one (then its
  /// counts go on: false). Not written anywhere (it came from the file). The new generation is
  /// logged with `why`.
  bool apply(std::size_t source, events::EventsConfig config, const std::string& why);

  /// Any thread: per source the geometry it counts now (runner/web_geometry.hpp), for the page.
  nlohmann::json geometry() const;

  /// The sources' frame sizes, for resolving a re-read file's sections.
  const std::vector<Source>& sources() const { return sources_; }

 private:
  // saving_ held: hands `config` to the metrics and the pipeline; returns its generation.
  std::uint32_t hand_over(std::size_t index, events::EventsConfig config);

  std::vector<Source> sources_;  // `running` guarded by saving_
  outputs::EventMetrics* metrics_;
  ConfigDocument& document_;
  const bool listed_;
  mutable std::mutex saving_;
  std::uint32_t generation_{0};  // of the last change, guarded by saving_
};

}  // namespace rtmot::runner
