#pragma once
// Everything `rtmot run` needs, read from a YAML file (docs/config.md lists every key). Strict: an
// unknown key, a wrong type or a bad value throws rtmot::InputError naming file, line and field.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "detector/dnn_backend.hpp"
#include "detector/ssd_defaults.hpp"
#include "detector/tile_layout.hpp"
#include "detector/tile_merge.hpp"
#include "detector/tile_request.hpp"
#include "events/events_yaml.hpp"
#include "outputs/mqtt_uri.hpp"
#include "outputs/overlay.hpp"
#include "outputs/video_encoding.hpp"
#include "outputs/video_target.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/playback_mode.hpp"
#include "platform/host_port.hpp"
#include "platform/oriented_source.hpp"
#include "tracker/enum_names.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::runner {

using pipeline::PlaybackMode;
using platform::HostPort;

enum class DetectorKind { ssd, replay };
inline constexpr auto kDetectorKindNames = tracker::make_enum_names<DetectorKind>(
    std::pair{DetectorKind::ssd, std::string_view("ssd")},
    std::pair{DetectorKind::replay, std::string_view("replay")});

struct SourceConfig {
  std::string uri;  // platform::open_video_source URI, or mot-seq://SEQUENCE_DIR (image-less)
  int width{0};     // requested camera size; 0 = the source's default
  int height{0};
  double fps{0.0};
  /// Stream id in this source's messages; -1 = the top-level stream_id + the source's index.
  std::int64_t stream_id{-1};
  /// Files: -1 = play for ever, N = N more passes after the first (platform/looping_source.hpp).
  int loop{0};
  /// Turned or mirrored before anything sees the frame (platform/oriented_source.hpp).
  platform::Orientation flip{platform::Orientation::none};
  /// `events:` lines and zones (docs/events.md), resolved against the frame once it is open.
  events::EventsSpec events;
};

struct PlaybackConfig {
  PlaybackMode mode{PlaybackMode::realtime};
  double latency_ms{250.0};  // simulated detector latency (simulated mode only)
};

// Every value below is parsed once, where it is read (runner/run_settings.cpp: the one table of
// names, docs and ranges); the defaults here are the documented ones (docs/config.md).
struct DetectorConfig {
  DetectorKind kind{DetectorKind::ssd};
  std::string model;    // ssd: model file
  std::string anchors;  // ssd: anchors CSV; empty = beside the model
  /// backend xnnpack-int8: the calibrated activation ranges; empty = the model's committed file.
  std::string int8_ranges;
  detector::BackendRequest backend{detector::BackendRequest::automatic};
  detector::Fp16Request fp16{detector::Fp16Request::automatic};
  float score_threshold{detector::kDefaultScoreThreshold};  // before the tracker sees anything
  float nms_threshold{detector::kDefaultNmsIou};
  /// The detector's CPU worker threads; 0 = every CPU this process may use. Decided (and set,
  /// process-wide) in one place: runner::make_detector.
  int threads{0};
  /// Batches in flight in the detect stage (its lanes, each a detector of its own); 0 = auto:
  /// 3 on CUDA, 1 otherwise. Decided in one place: runner::make_detectors.
  int in_flight{0};
  /// ssd: the classes to keep, as given: names of the model's labels or column numbers, resolved
  /// against the model's labels by runner/class_choice.hpp; empty = all.
  std::vector<std::string> classes{"person"};
  std::string det_file;  // replay: a MOTChallenge det.txt
  /// ssd: the frame in overlapping tiles with the whole (docs/tiling.md); auto is decided in one
  /// place: runner/tiling_choice.hpp.
  detector::TileRequest tiles;
  float tile_overlap{detector::TileGrid{}.overlap};
  float tile_threshold{detector::TileMergeConfig{}.tile_score_threshold};
  /// ssd: drop boxes of shapes their class does not have (detector/box_plausibility.hpp).
  bool plausible_shapes{true};
  /// A colour signature per detection from the image (vision/), used where the tracker's
  /// appearance gate or weight is on.
  bool appearance{true};
  /// Between detections, follow the tracks' boxes in the image (vision/box_follower.hpp;
  /// docs/full-rate.md, "Observed boxes").
  bool follow_image{true};
};

struct OutputConfig {
  std::optional<HostPort> udp;  // off when absent
  std::string binary_file;      // empty = off
  std::string jsonl_file;       // empty = off
  std::optional<outputs::MqttUri> mqtt;
  std::optional<outputs::VideoTarget> video;  // the annotated video (output.video_file)
  outputs::VideoEncoding video_encoding;      // its codec, encoder and bitrate
  outputs::OverlayFlags overlay{~0U};         // what the video shows: every flag
  std::string report_file;                    // JSON report, empty = off
  int metrics_port{0};                        // Prometheus endpoint on this TCP port, 0 = off
  std::string metrics_bind{"127.0.0.1"};      // an IP literal the endpoint listens on
  double metrics_linger_s{0.0};               // the final metrics served this long after the run
  int web_port{0};                            // the operator's page on this TCP port, 0 = off
  std::string web_bind{"127.0.0.1"};          // an IP literal the page listens on
  std::string web_token_file;                 // the token writes need; empty: writes are off
  /// Where the page's saves go (a whole configuration: --config's with the change); empty: the
  /// --config file itself.
  std::string web_save_to;
  /// MOTChallenge results per source, in this folder (runner/mot_results_output.hpp); empty = off.
  std::string mot_results;
  /// With mot_results: also NAME.det.txt, every processed frame's detections as the tracker got
  /// them (a MOTChallenge det.txt: replayed by detector.det_file, read by rtmot track).
  bool mot_detections{false};
  /// A message for every camera frame, predicted where the detector skipped (docs/full-rate.md).
  bool full_rate{false};
};

struct RunConfig {
  std::string file;  // where it was read from (for messages)
  /// The configuration file it was loaded from (--config), where the page's saves go; empty when
  /// the run has none (defaults and flags only: `file` then says "(command line)").
  std::string loaded_from;
  /// The line each setting was read from in `file` ("detector.classes" -> 3), for checks made
  /// once every setting is known; a flag that overrides one removes its line.
  std::map<std::string, int> lines;
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

/// Replaces `config`'s tracker with the preset `name` (false if there is none): the one way a
/// preset is applied, for the YAML `tracker: {preset: ...}`, `run --preset` and `track --preset`.
/// What the preset does not fix (frame rate, image size) stays "from the source" (0).
bool apply_preset(std::string_view name, tracker::TrackerConfig& config);

/// Why `source` cannot be turned as its `flip` asks, or nullopt when it can (or asks nothing):
/// a mot-seq:// sequence has no frames, only the det file's boxes in the sequence's own
/// orientation; turning its size alone put every box and every event shape off its frame.
/// validate() refuses it from a file (exit 3), RunFlags from --input-flip (exit 2).
std::optional<std::string> flip_problem(const SourceConfig& source);

/// Checks what only the complete configuration (file plus command-line overrides) can tell: a
/// source is given, the detector has its model or det file, outputs are consistent. Throws
/// InputError.
void validate(const RunConfig& config);

/// The ssd detector's model file exists (where it was looked for otherwise: exit 4). Separate from
/// validate(): the outputs are checked first (prepare_video_output), and a configuration can be
/// checked without the model at hand.
void check_model_found(const RunConfig& config);

}  // namespace rtmot::runner
