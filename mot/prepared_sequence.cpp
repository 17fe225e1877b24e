#include "mot/prepared_sequence.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include "common/input_error.hpp"
#include "mot/box_iou.hpp"
#include "tracker/linear_assignment.hpp"

namespace rtmot::mot {

namespace {

constexpr int kPedestrian = 1;

bool has_class_column(const std::vector<motio::MotRow>& gt_rows) {
  return std::any_of(gt_rows.begin(), gt_rows.end(),
                     [](const motio::MotRow& row) { return row.class_id >= 0; });
}

/// Row indices grouped by frame.
std::map<int, std::vector<std::size_t>> rows_by_frame(const std::vector<motio::MotRow>& rows) {
  std::map<int, std::vector<std::size_t>> frames;
  for (std::size_t i = 0; i < rows.size(); ++i) frames[rows[i].frame].push_back(i);
  return frames;
}

// The devkit's preprocessResult: per frame, a min-cost matching of all gt boxes (any class, any
// conf) with the result boxes on 1 - IoU, pairs below IoU 0.5 forbidden; a result box matched to a
// distractor or to a too-occluded box is dropped.
std::vector<bool> results_to_keep(const std::vector<motio::MotRow>& gt_rows,
                                  const std::vector<motio::MotRow>& result_rows,
                                  double min_visibility) {
  std::vector<bool> keep(result_rows.size(), true);
  const auto gt_frames = rows_by_frame(gt_rows);
  const auto result_frames = rows_by_frame(result_rows);
  tracker::LinearAssignment solver;
  std::vector<double> cost;
  for (const auto& [frame, result_indices] : result_frames) {
    const auto found = gt_frames.find(frame);
    if (found == gt_frames.end()) continue;
    const auto& gt_indices = found->second;
    const int rows = static_cast<int>(gt_indices.size());
    const int cols = static_cast<int>(result_indices.size());
    // Forbidden pairs cost more than any set of allowed ones, so the matching is of largest size
    // first, as with the devkit's infinite costs.
    const double forbidden = 1.0 + std::min(rows, cols);
    cost.assign(static_cast<std::size_t>(rows) * cols, forbidden);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        const double distance =
            1.0 - box_iou(gt_rows[gt_indices[r]].box, result_rows[result_indices[c]].box);
        if (distance <= 0.5) cost[static_cast<std::size_t>(r) * cols + c] = distance;
      }
    }
    const auto& assignment = solver.solve(cost.data(), rows, cols);
    for (int r = 0; r < rows; ++r) {
      const int c = assignment[r];
      if (c < 0 || cost[static_cast<std::size_t>(r) * cols + c] >= forbidden) continue;
      const motio::MotRow& gt = gt_rows[gt_indices[r]];
      if (is_distractor_class(gt.class_id) || gt.visibility < min_visibility) {
        keep[result_indices[c]] = false;
      }
    }
  }
  return keep;
}

/// Maps sparse ids to 0..n-1 in increasing order (the devkit's unique()).
std::map<int, int> dense_ids(const std::vector<const motio::MotRow*>& rows) {
  std::map<int, int> ids;
  for (const motio::MotRow* row : rows) ids.emplace(row->id, 0);
  int next = 0;
  for (auto& [id, dense] : ids) dense = next++;
  return ids;
}

// Which frames are scored, and as which timestep: every interval-th, or those of a list.
class FrameSteps {
 public:
  explicit FrameSteps(const PrepareOptions& options)
      : interval_(options.interval), frames_(options.frames) {}
  bool scored(int frame) const {
    if (frames_.empty()) return (frame - 1) % interval_ == 0;
    return std::binary_search(frames_.begin(), frames_.end(), frame);
  }
  /// The timestep of a scored frame.
  int step(int frame) const {
    if (frames_.empty()) return (frame - 1) / interval_;
    return static_cast<int>(std::lower_bound(frames_.begin(), frames_.end(), frame) -
                            frames_.begin());
  }
  /// Timesteps up to and including `last_frame`.
  int steps_through(int last_frame) const {
    if (last_frame < 1) return 0;
    if (frames_.empty()) return (last_frame - 1) / interval_ + 1;
    return static_cast<int>(std::upper_bound(frames_.begin(), frames_.end(), last_frame) -
                            frames_.begin());
  }

 private:
  int interval_;
  const std::vector<int>& frames_;
};

std::vector<TimestepBoxes> to_timesteps(const std::vector<const motio::MotRow*>& rows,
                                        const std::map<int, int>& ids, const FrameSteps& steps_of,
                                        int timesteps, const std::string& file) {
  std::vector<std::vector<const motio::MotRow*>> per_step(static_cast<std::size_t>(timesteps));
  for (const motio::MotRow* row : rows)
    per_step[static_cast<std::size_t>(steps_of.step(row->frame))].push_back(row);
  std::vector<TimestepBoxes> steps(static_cast<std::size_t>(timesteps));
  for (std::size_t t = 0; t < per_step.size(); ++t) {
    auto& in_step = per_step[t];
    std::sort(in_step.begin(), in_step.end(),
              [](const motio::MotRow* a, const motio::MotRow* b) { return a->id < b->id; });
    for (std::size_t i = 0; i < in_step.size(); ++i) {
      if (i > 0 && in_step[i]->id == in_step[i - 1]->id) {
        throw InputError(file, 0, "id",
                         "id " + std::to_string(in_step[i]->id) + " appears twice in frame " +
                             std::to_string(in_step[i]->frame));
      }
      steps[t].ids.push_back(ids.at(in_step[i]->id));
      steps[t].boxes.push_back(in_step[i]->box);
    }
  }
  return steps;
}

}  // namespace

bool is_distractor_class(int class_id) {
  // person on vehicle, static person, distractor, reflection
  return class_id == 2 || class_id == 7 || class_id == 8 || class_id == 12;
}

PreparedSequence prepare_sequence(const std::vector<motio::MotRow>& gt_rows,
                                  const std::vector<motio::MotRow>& result_rows,
                                  const PrepareOptions& options) {
  if (options.interval < 1) {
    throw InputError("", 0, "interval", "must be at least 1", ExitCode::usage);
  }
  const FrameSteps steps_of(options);
  const auto scored = [&](int frame) { return steps_of.scored(frame); };
  const bool with_classes = has_class_column(gt_rows);
  const std::vector<bool> keep_result =
      with_classes ? results_to_keep(gt_rows, result_rows, options.min_visibility)
                   : std::vector<bool>(result_rows.size(), true);

  std::vector<const motio::MotRow*> gt;
  for (const motio::MotRow& row : gt_rows) {
    const bool counted = row.conf != 0.F && (!with_classes || row.class_id == kPedestrian);
    if (counted && scored(row.frame)) gt.push_back(&row);
  }
  int last_frame = options.sequence_length;
  if (!gt.empty()) {
    last_frame = (*std::max_element(gt.begin(), gt.end(),
                                    [](const motio::MotRow* a, const motio::MotRow* b) {
                                      return a->frame < b->frame;
                                    }))
                     ->frame;
  }
  std::vector<const motio::MotRow*> results;
  for (std::size_t i = 0; i < result_rows.size(); ++i) {
    const motio::MotRow& row = result_rows[i];
    // The devkit clips results to the last gt frame.
    if (keep_result[i] && scored(row.frame) && row.frame <= last_frame) results.push_back(&row);
  }

  PreparedSequence sequence;
  const int timesteps = steps_of.steps_through(last_frame);
  const auto gt_ids = dense_ids(gt);
  const auto result_ids = dense_ids(results);
  sequence.num_gt_ids = static_cast<int>(gt_ids.size());
  sequence.num_result_ids = static_cast<int>(result_ids.size());
  sequence.gt = to_timesteps(gt, gt_ids, steps_of, timesteps, options.gt_file);
  sequence.results = to_timesteps(results, result_ids, steps_of, timesteps, options.results_file);
  for (int t = timesteps - 1; t >= 0; --t) {
    if (!sequence.results[static_cast<std::size_t>(t)].ids.empty()) {
      sequence.last_result_timestep = t;
      break;
    }
  }
  return sequence;
}

}  // namespace rtmot::mot
