#include "mot/study_dataset.hpp"

#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "motio/sequence_folders.hpp"
#include "motio/track_runner.hpp"

namespace rtmot::mot {

namespace fs = std::filesystem;

std::string_view to_string(StudyInput input) {
  return input == StudyInput::detections ? "det" : "gt";
}

std::vector<LoadedSequence> load_study_dataset(const fs::path& dataset) {
  std::vector<LoadedSequence> sequences;
  for (const motio::SequenceFolder& folder : motio::find_sequences(dataset)) {
    const fs::path& dir = folder.dir;
    LoadedSequence sequence;
    sequence.info = folder.info;
    const fs::path gt_file = dir / "gt" / "gt.txt";
    sequence.gt_rows =
        motio::read_mot_file(gt_file, motio::MotFileKind::ground_truth, sequence.info.length);
    sequence.detections = motio::load_detections(dir / "det" / "det.txt", sequence.info);
    sequence.gt_detections = motio::load_detections(gt_file, sequence.info);
    sequences.push_back(std::move(sequence));
  }
  return sequences;
}

SequenceCounts track_and_count(const LoadedSequence& sequence, StudyInput input,
                               const tracker::TrackerConfig& config, int interval) {
  motio::TrackOptions options;
  options.config = config;
  options.interval = interval;
  const motio::TrackRun run = motio::track_detections(
      input == StudyInput::detections ? sequence.detections : sequence.gt_detections, sequence.info,
      options);
  PrepareOptions prepare;
  prepare.interval = interval;
  prepare.sequence_length = sequence.info.length;
  prepare.gt_file = sequence.info.name + "/gt/gt.txt";
  prepare.results_file = sequence.info.name + " (tracked in memory)";
  return count_all(prepare_sequence(sequence.gt_rows, run.tracks, prepare));
}

Metrics track_and_score(const std::vector<LoadedSequence>& dataset, StudyInput input,
                        const tracker::TrackerConfig& config, int interval) {
  SequenceCounts total;
  for (const auto& sequence : dataset) total += track_and_count(sequence, input, config, interval);
  return summarize(total);
}

}  // namespace rtmot::mot
