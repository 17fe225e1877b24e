#pragma once
// Everything `rtmot run` needs, read from a YAML file (docs/config.md lists every key). Strict: an
// unknown key, a wrong type or a bad value throws rtmot::InputError naming file, line and field.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "events/events_yaml.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/playback_mode.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::runner {

using pipeline::PlaybackMode;

struct SourceConfig {
  std::string uri;  // platform::open_video_source URI, or mot-seq://SEQUENCE_DIR (image-less)
  int width{0};     // requested camera size; 0 = the source's default
  int height{0};
  double fps{0.0};
  /// Stream id in this source's messages; -1 = the top-level stream_id + the source's index.
  std::int64_t stream_id{-1};
  /// `events:` lines and zones (docs/events.md), resolved against the frame once it is open.
  events::EventsSpec events;
};

struct PlaybackConfig {
  PlaybackMode mode{PlaybackMode::realtime};
  double latency_ms{250.0};  // simulated detector latency (simulated mode only)
};

struct DetectorConfig {
  std::string kind{"ssd"};      // ssd | replay
  std::string model;            // ssd: model file
  std::string anchors;          // ssd: anchors CSV; empty = beside the model
  std::string backend{"auto"};  // auto | cpu | cuda
  std::string fp16{"auto"};     // auto | on | off (true/false accepted)
  float score_threshold{0.5F};
  float nms_threshold{0.6F};
  int threads{0};               // OpenCV worker threads; 0 = OpenCV's default
  std::vector<int> classes{1};  // COCO ids to keep (1 = person); empty = all
  std::string det_file;         // replay: a MOTChallenge det.txt
};

struct OutputConfig {
  std::string udp;          // HOST:PORT, empty = off
  std::string binary_file;  // empty = off
  std::string jsonl_file;   // empty = off
  std::string mqtt;         // mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json], empty = off
  std::string video_file;  // annotated video by path or URI (outputs/video_target.hpp), empty = off
  std::string overlay{"box,labels,conf,track,trail,stats"};  // what the video shows
  std::string report_file;                                   // JSON report, empty = off
  int metrics_port{0};                    // Prometheus endpoint on this TCP port, 0 = off
  std::string metrics_bind{"127.0.0.1"};  // address the endpoint listens on
};

struct RunConfig {
  std::string file;     // where it was read from (for messages)
  SourceConfig source;  // one source (`source:`, or one --source)
  std::vector<SourceConfig>
      sources;  // several (`sources:` or --source repeated); replaces `source`
  PlaybackConfig playback;
  DetectorConfig detector;
  /// frame_rate, image_width and image_height are 0 unless the file sets them: then the pipeline
  /// takes them from the source.
  tracker::TrackerConfig tracker;
  OutputConfig output;
  pipeline::StageThreads threads;  // per stage: CPU pinning and SCHED_FIFO priority
  double stats_interval_s{5.0};    // periodic log line; 0 = off
  std::uint32_t stream_id{0};
  std::int64_t max_frames{0};  // stop after this many captured frames; 0 = no limit
};

/// The sources to run: `sources` if given, else the one `source`.
std::vector<SourceConfig> source_list(const RunConfig& config);
/// The stream id of source `index` of source_list().
std::uint32_t stream_id_of(const RunConfig& config, std::size_t index);

/// Reads a YAML run configuration. Relative paths in it stay as written (relative to the cwd).
RunConfig load_run_config(const std::string& path);
/// The configuration without a file: every default of docs/config.md (tracker preset `rtmot`, the
/// model scripts/fetch_model.sh writes); the command line supplies the rest.
RunConfig default_run_config();
/// Same, from text; `file_name` names it in errors.
RunConfig parse_run_config(const std::string& yaml_text, const std::string& file_name);

/// Checks what only the complete configuration (file plus command-line overrides) can tell: a
/// source is given, the detector has its model or det file, outputs are consistent. Throws
/// InputError.
void validate(const RunConfig& config);

}  // namespace rtmot::runner
