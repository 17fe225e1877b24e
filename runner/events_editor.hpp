#pragma once
// The web page's "save lines" (docs/web.md): the posted events section (YAML or JSON, as the
// configuration file's `events:`) is read by the file's own reader (events/events_yaml.hpp) and
// resolved against the source's frame; any error is answered with its field and leaves the run as
// it was. A valid one is handed to the running pipeline (pipeline/events_mailbox.hpp: the track
// stage counts it from its next frame, from zero), to the metrics (EventMetrics::post) and written
// back into the run's configuration file, whole or not at all (common/output_file.hpp, published on
// close).
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "outputs/event_metrics.hpp"
#include "outputs/web_server.hpp"
#include "pipeline/events_mailbox.hpp"

namespace rtmot::runner {

class EventsEditor {
 public:
  struct Source {
    std::uint32_t stream_id{0};
    std::string uri;
    int width{0};
    int height{0};
    double frame_period_seconds{0.0};
    pipeline::EventsMailbox* mailbox{nullptr};  // not owned
  };

  /// `config_file`: where a saved section is written back ("" for a run without one: not saved);
  /// `listed`: the file lists its sources under `sources:` (else one `source:`).
  EventsEditor(std::vector<Source> sources, outputs::EventMetrics& metrics, std::string config_file,
               bool listed);

  /// Any thread (saves are serialised): the answer to POST /api/events?source=N.
  outputs::SaveAnswer save(std::size_t source, const std::string& body);

 private:
  std::vector<Source> sources_;
  outputs::EventMetrics& metrics_;
  const std::string config_file_;
  const bool listed_;
  std::mutex saving_;
  std::uint32_t generation_{0};  // of the last save, guarded by saving_
};

}  // namespace rtmot::runner
