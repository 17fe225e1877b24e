#include "study/study_dataset.hpp"

#include <fmt/format.h>

#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "motio/sequence_folders.hpp"
#include "motio/track_runner.hpp"
#include "study/synthetic_detector.hpp"

namespace rtmot::study {

namespace fs = std::filesystem;

std::string_view to_string(StudyInput input) {
  switch (input.kind) {
    case StudyInput::Kind::detections:
      return "det";
    case StudyInput::Kind::ground_truth:
      return "gt";
    case StudyInput::Kind::synthetic:
      return synthetic_detectors().at(static_cast<std::size_t>(input.synthetic)).name;
  }
  return "?";
}

std::string input_title(StudyInput input) {
  switch (input.kind) {
    case StudyInput::Kind::detections:
      return "det/det.txt";
    case StudyInput::Kind::ground_truth:
      return "gt/gt.txt (perfect detector)";
    case StudyInput::Kind::synthetic: {
      const auto& spec = synthetic_detectors().at(static_cast<std::size_t>(input.synthetic));
      return fmt::format(
          "{} ({}synthetic: {} scores, misses {:g} in runs of {:g}, {:g} random FP "
          "per frame + {} clutter sites at {:g}, jitter {:g}, separation {:g})",
          spec.name, spec.held_back ? "held back from every choice; " : "",
          kScoreScaleNames.name(spec.scale), spec.miss_rate, spec.miss_run_frames,
          spec.false_per_frame, spec.clutter_sites, spec.clutter_rate, spec.jitter,
          spec.separation);
    }
  }
  return "?";
}

namespace {

std::vector<StudyInput> synthetic_inputs_held_back(bool held_back) {
  std::vector<StudyInput> inputs;
  for (std::size_t i = 0; i < synthetic_detectors().size(); ++i) {
    if (synthetic_detectors()[i].held_back == held_back)
      inputs.push_back(StudyInput::synthetic_detector(static_cast<int>(i)));
  }
  return inputs;
}

}  // namespace

std::vector<StudyInput> synthetic_inputs() {
  return synthetic_inputs_held_back(false);
}

std::vector<StudyInput> held_back_inputs() {
  return synthetic_inputs_held_back(true);
}

bool is_held_back(const StudyInput& input) {
  return input.kind == StudyInput::Kind::synthetic &&
         synthetic_detectors().at(static_cast<std::size_t>(input.synthetic)).held_back;
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
    for (const auto& spec : synthetic_detectors()) {
      sequence.synthetic.push_back(motio::FrameDetections::from_frames(synthesize_detections(
          spec, sequence.gt_rows, sequence.info, static_cast<int>(sequences.size()))));
    }
    sequences.push_back(std::move(sequence));
  }
  return sequences;
}

mot::SequenceCounts track_and_count(const LoadedSequence& sequence, StudyInput input,
                                    const tracker::TrackerConfig& config, int interval,
                                    const StudyKnobs& knobs) {
  motio::TrackOptions options;
  options.config = config;
  options.extension = study_extension(knobs, config);
  options.interval = interval;
  const motio::FrameDetections& detections =
      input.kind == StudyInput::Kind::detections ? sequence.detections
      : input.kind == StudyInput::Kind::ground_truth
          ? sequence.gt_detections
          : sequence.synthetic.at(static_cast<std::size_t>(input.synthetic));
  const motio::TrackRun run = motio::track_detections(detections, sequence.info, options);
  mot::PrepareOptions prepare;
  prepare.interval = interval;
  prepare.sequence_length = sequence.info.length;
  prepare.gt_file = sequence.info.name + "/gt/gt.txt";
  prepare.results_file = sequence.info.name + " (tracked in memory)";
  return mot::count_all(mot::prepare_sequence(sequence.gt_rows, run.tracks, prepare));
}

mot::Metrics track_and_score(const std::vector<LoadedSequence>& dataset, StudyInput input,
                             const tracker::TrackerConfig& config, int interval,
                             const StudyKnobs& knobs) {
  mot::SequenceCounts total;
  for (const auto& sequence : dataset)
    total += track_and_count(sequence, input, config, interval, knobs);
  return mot::summarize(total);
}

}  // namespace rtmot::study
