#pragma once
// `rtmot study --latency`: the tracker behind a detector that is slower than the camera, with the
// pipeline's own frame skipping (common/simulated_clock.hpp: the detector, when free, takes the
// newest frame; everything in between is skipped) on a simulated clock, so every run processes
// the same frames on any machine. For each detector latency (fixed, or jittered per frame) the
// presets track exactly the frames that pipeline would process, and are scored twice: on those
// frames (how well it tracks what it sees) and at the full frame rate (what a user of the output
// gets: every skipped frame's boxes missed). The seed's Figure 4.4 made with our scheduling. And
// a third time with the full-rate output (predicted boxes at the skipped frames), at every frame.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mot/metrics.hpp"
#include "motio/mot_files.hpp"
#include "study/study_dataset.hpp"

namespace rtmot::study {

struct DetectorLatency {
  double latency_ms{0.0};  // 0: a detector faster than the camera (every frame)
  /// 0: every frame takes latency_ms. Else each frame the detector takes costs a latency drawn
  /// uniformly in [(1 - jitter), (1 + jitter)] x latency_ms (mean latency_ms), seeded per
  /// sequence.
  double jitter{0.0};
  /// When > 0: the latency is this many of each sequence's own frame periods instead of
  /// latency_ms (5: every 5th frame processed, 4 of 5 skipped, at any frame rate).
  double frames{0.0};
};

/// "125 ms", "125 ms ±50%" or "5 frames" (file- and table-safe: no commas).
std::string latency_label(const DetectorLatency& latency);

/// 0 (every frame), then 33, 66, 125, 250, 500 and 1000 ms fixed, then the same jittered ±50 %,
/// then 5 and 10 frame periods (4 of 5 and 9 of 10 frames skipped in every sequence).
std::vector<DetectorLatency> default_latencies();

/// The frames (ascending) a pipeline in `simulated` playback processes of a sequence with `info`'s
/// rate and length when its detector takes `latency`; `seed` draws a jittered latency.
std::vector<int> pipeline_frames(const motio::SequenceInfo& info, const DetectorLatency& latency,
                                 std::uint64_t seed);

struct LatencyRow {
  DetectorLatency latency;
  std::int64_t frames_processed{0};
  std::int64_t frames{0};  // of every sequence
  mot::Metrics processed;  // scored on the processed frames
  mot::Metrics full_rate;  // scored at every frame
  /// Full-rate output (docs/full-rate.md): the processed frames' boxes plus, at every skipped
  /// frame, each reported track's prediction for its time; scored at every frame.
  mot::Metrics full_rate_output;
  /// The same with every reported track predicted (min_hits 0), not only those matched twice in a
  /// row (tracker::kPredictedMinHits): what that rule gains and costs.
  mot::Metrics full_rate_output_every;
  std::int64_t frames_predicted{0};
};

struct LatencyTable {
  std::string preset;  // a tracker preset's name (tracker/presets.hpp)
  StudyInput input{StudyInput::detections};
  std::vector<LatencyRow> rows;  // one per latency, in the order asked
};

/// Every preset x input x latency over all sequences pooled, on `jobs` threads. `stop` (may be
/// null): once true no further run starts (the tables are then incomplete: discard them).
std::vector<LatencyTable> run_latency_sweep(const std::vector<LoadedSequence>& dataset,
                                            const std::vector<std::string>& presets,
                                            const std::vector<StudyInput>& inputs,
                                            const std::vector<DetectorLatency>& latencies, int jobs,
                                            const std::atomic<bool>* stop = nullptr);

std::string format_latency_markdown(const LatencyTable& table);
std::string format_latency_csv(const LatencyTable& table);

/// OUT/latency/<input>-<preset>.{md,csv}, OUT/latency/<input>-{mota,idf1}-{processed,full}.svg
/// and OUT/latency/summary.md (every table, the plots linked). Returns the files.
std::vector<std::filesystem::path> write_latency_sweep(const std::filesystem::path& out_dir,
                                                       const std::vector<LatencyTable>& tables);

}  // namespace rtmot::study
