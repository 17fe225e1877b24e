#pragma once
// Detectors made from the ground truth, with controlled misses (in runs, as occlusions make them),
// false positives (random and at fixed clutter sites), box jitter and a score scale of their own:
// stress tests of the tracker on detectors it was never tuned on (docs/study.md, "synthetic").
// Seeded and portable: the random numbers come from std::mt19937_64's raw output (its sequence is
// fixed by the standard), turned into uniforms and normals here rather than by the standard
// library's distributions, whose algorithms differ between implementations.
#include <cstdint>
#include <string>
#include <vector>

#include "motio/mot_files.hpp"
#include "tracker/box.hpp"
#include "tracker/enum_names.hpp"

namespace rtmot::study {

/// How a latent confidence z (true positives around `separation`, false positives around 0, unit
/// spread) is reported.
enum class ScoreScale {
  frcnn,    // 0.5 + 0.5 sigmoid(z): 0.5..1, as MOT15's public Faster R-CNN detections
  sigmoid,  // sigmoid(z - 1): 0..1 with its own calibration, as an SSD
  dpm,      // 1.2 z + 0.5: about -2..5, as a DPM's SVM margins
  percent,  // 100 sigmoid(z): 0..100
  logit,    // 2 z: unbounded, centred on 0
  // Floor-heavy, long-tailed shapes: most detections (the false ones) pile up just above the
  // detector's own threshold and the true ones spread over a long upper tail, as unbounded margins
  // and un-squashed network outputs do. A fraction of such a range lies far up the tail.
  exp,        // exp(1.5 z): about 0.2..500, an un-squashed (exponentiated) network output
  exp_steep,  // exp(3 z): about 0.05..2e5, the same with a steeper tail
  square,     // (z + 1)^2: 0..about 35, a margin above the detector's threshold, squared
  sinh,       // sinh(1.5 z): about -2..300, a margin with heavy tails
};

inline constexpr auto kScoreScaleNames = tracker::make_enum_names<ScoreScale>(
    std::pair{ScoreScale::frcnn, "frcnn"}, std::pair{ScoreScale::sigmoid, "sigmoid"},
    std::pair{ScoreScale::dpm, "dpm"}, std::pair{ScoreScale::percent, "percent"},
    std::pair{ScoreScale::logit, "logit"}, std::pair{ScoreScale::exp, "exp"},
    std::pair{ScoreScale::exp_steep, "exp_steep"}, std::pair{ScoreScale::square, "square"},
    std::pair{ScoreScale::sinh, "sinh"});

struct SyntheticDetectorSpec {
  std::string name;             // "synth-dpm": the study's input name
  double miss_rate{0.2};        // chance per track and frame that a miss run starts
  double miss_run_frames{3.0};  // mean length of a miss run (geometric)
  double false_per_frame{1.0};  // random false positives per frame (Poisson)
  int clutter_sites{2};         // fixed background boxes per sequence...
  double clutter_rate{0.3};     // ...each detected in a frame with this chance
  double jitter{0.05};          // box noise: position sd as a share of the size; log-size sd
  double separation{1.5};       // true positives' latent mean over false positives'
  double latent_floor{-1.0};    // the detector's own threshold on z: below it, nothing is output
  ScoreScale scale{ScoreScale::frcnn};
  std::uint64_t seed{1};
  /// Held back from every choice: no grid or fold sees it; only the presets run on it, after the
  /// default was chosen. A test set for the shipped default, where the folds test the procedure.
  bool held_back{false};
};

/// The study's synthetic detectors: those the cross-validation chooses on (`synth-`) and those held
/// back (`holdout-`), each written down before any run on it (docs/study.md lists all and when).
const std::vector<SyntheticDetectorSpec>& synthetic_detectors();

/// The detections `spec` makes of one sequence, by frame (index frame - 1). `gt_rows` as read from
/// gt/gt.txt; rows the benchmark ignores (conf 0, non-pedestrian classes) are not detected.
/// `sequence_index` decorrelates sequences that share a seed.
std::vector<std::vector<tracker::Detection>> synthesize_detections(
    const SyntheticDetectorSpec& spec, const std::vector<motio::MotRow>& gt_rows,
    const motio::SequenceInfo& info, int sequence_index);

}  // namespace rtmot::study
