#pragma once
// `output.mot_results` (`--mot-results DIR`): the tracks of every source as MOTChallenge results,
// DIR/NAME.txt, and the frames the pipeline processed, DIR/NAME.frames (motio/processed_frames),
// so that `rtmot eval --processed-frames` scores a real-time run on the frames it saw and plain
// `rtmot eval` at the full frame rate. The frames a slow detector made the pipeline skip have no
// rows: they are what gets scored as skipped; with full-rate output (output.full_rate) they have
// the predicted rows, and NAME.frames still lists the processed frames only, so eval scores the
// run both ways (docs/full-rate.md).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "motio/detections_writer.hpp"
#include "motio/results_writer.hpp"
#include "pipeline/frame_consumer.hpp"
#include "runner/run_config.hpp"

namespace rtmot::runner {

/// Where one source's results go: its stream id and the NAME of NAME.txt / NAME.frames.
struct MotResultsTarget {
  std::uint32_t stream_id{0};
  std::string name;
};

/// The name a source's results are filed under, so that `rtmot eval --gt` finds them: a
/// MOTChallenge sequence's own (its seqinfo.ini's `name`) for `mot-seq://SEQ` and for an image
/// folder that is SEQ or SEQ/img1; else a file's or folder's name without extension; else (cameras,
/// streams, test://) `stream-ID`. Names not read from a seqinfo.ini have characters other than
/// letters, digits and `- _ . +` replaced by `_`. Throws InputError naming a malformed seqinfo.ini.
std::string mot_results_name(const SourceConfig& source, std::uint32_t stream_id);

/// Every source's target, in source_list() order. Throws InputError (field output.mot_results)
/// when two sources would write the same name.
std::vector<MotResultsTarget> mot_results_targets(const RunConfig& config);

/// DIR/NAME.txt and DIR/NAME.frames.
std::filesystem::path mot_results_file(const std::filesystem::path& dir, const std::string& name);
std::filesystem::path mot_frames_file(const std::filesystem::path& dir, const std::string& name);
/// DIR/NAME.det.txt (output.mot_detections).
std::filesystem::path mot_detections_file(const std::filesystem::path& dir,
                                          const std::string& name);

/// The consumer. Both files of a source (three with the detections) appear whole at finish()
/// (also after a failure: what was tracked until then is kept, and the frames file says which
/// frames that was); a run killed before leaves none (common/output_file.hpp). Outage ticks are no
/// processed frame.
class MotResultsOutput : public pipeline::FrameConsumer {
 public:
  /// Creates `dir` (and its parents) and every results file's temporary; throws InputError
  /// (output.mot_results) when it cannot. `with_detections`: also NAME.det.txt, the processed
  /// frames' SinkFrame::detections (the pipeline must keep them: keep_detections).
  MotResultsOutput(const std::filesystem::path& dir, const std::vector<MotResultsTarget>& targets,
                   bool with_detections = false);

  void consume(const pipeline::SinkFrame& frame) override;
  void finish() override;

 private:
  struct Stream {
    std::uint32_t stream_id;
    std::filesystem::path frames_file;
    motio::ResultsWriter results;
    std::optional<motio::DetectionsWriter> detections;  // with_detections only
    std::vector<int> frames;                            // processed, ascending
    int last_written{0};  // the last frame given rows, processed or predicted
  };
  std::vector<Stream> streams_;
  bool finished_{false};
};

}  // namespace rtmot::runner
