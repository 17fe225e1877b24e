#pragma once
// A sequence's ground truth and results reduced to what the metrics need, after the benchmark's
// rules: which gt rows count, which result boxes are removed, which frames are scored.
#include <string>
#include <vector>

#include "motio/mot_files.hpp"
#include "tracker/box.hpp"

namespace rtmot::mot {

/// The boxes of one scored frame, sorted by id. Ids are dense: 0..count-1 over the sequence.
struct TimestepBoxes {
  std::vector<int> ids;
  std::vector<tracker::Box> boxes;
};

struct PreparedSequence {
  std::vector<TimestepBoxes> gt;       // one per scored frame
  std::vector<TimestepBoxes> results;  // same length as gt
  int num_gt_ids{0};
  int num_result_ids{0};
  /// The last timestep holding a result box, -1 if none (the devkit's MT/PT/ML rule needs it).
  int last_result_timestep{-1};
};

struct PrepareOptions {
  /// Score frames 1, 1 + interval, 1 + 2 * interval, ... only.
  int interval{1};
  /// When not empty: score exactly these frames (ascending; motio/processed_frames.hpp), each a
  /// timestep, instead of by `interval`.
  std::vector<int> frames;
  /// MOT16/17 gt: result boxes matched to a gt box less visible than this are removed (devkit's
  /// minvis, 0 in the benchmark).
  double min_visibility{0.0};
  /// Used when no gt row remains, to count the frames.
  int sequence_length{0};
  /// For error messages.
  std::string gt_file;
  std::string results_file;
};

/// Applies the MOTChallenge devkit's rules: gt rows with conf 0 are ignored; with a class column
/// (MOT16/17/20 gt), result boxes matched (IoU >= 0.5, Hungarian) to a distractor are removed and
/// only pedestrians (class 1) stay in the gt; results after the last gt frame are dropped. Throws
/// InputError on an id that appears twice in one frame.
PreparedSequence prepare_sequence(const std::vector<motio::MotRow>& gt_rows,
                                  const std::vector<motio::MotRow>& result_rows,
                                  const PrepareOptions& options);

/// MOT16/17 classes whose matched result boxes are removed before scoring (MOT20 adds 6).
bool is_distractor_class(int class_id);

}  // namespace rtmot::mot
