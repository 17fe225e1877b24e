// CLEAR MOT as the MOTChallenge devkit (clearMOTMex.cpp, CLEAR_MOT_HUN.m) computes it, quirks
// included, so that our figures equal the benchmark's:
// - a gt box keeps last frame's partner if it is still there with IoU >= 0.5, the rest are
//   matched by a min-cost assignment on 1 - IoU (largest matching first, ties broken by order);
// - an ID switch is counted only when the gt box was also present in the previous frame;
// - a track with coverage in [0.2, 0.8] counts as partly tracked only if the results reach its
//   last frame (the devkit leaves it unclassified otherwise).
#include <algorithm>

#include "mot/box_iou.hpp"
#include "mot/scorer.hpp"
#include "tracker/linear_assignment.hpp"

namespace rtmot::mot {

namespace {

constexpr double kMaxDistance = 0.5;  // 1 - IoU threshold
constexpr int kNone = -1;

// Per gt track, what the metrics need across frames.
struct GtTrackState {
  int previous_partner{kNone};  // result id matched in the previous timestep
  int last_partner{kNone};      // result id of the last match, however long ago
  bool present_previously{false};
  bool tracked_previously{false};
  bool ever_tracked{false};
  int frames_present{0};
  int frames_tracked{0};
  int last_timestep{kNone};
};

int find_index(const std::vector<int>& ids, int id) {
  const auto found = std::lower_bound(ids.begin(), ids.end(), id);
  return found != ids.end() && *found == id ? static_cast<int>(found - ids.begin()) : kNone;
}

}  // namespace

ClearCounts count_clear(const PreparedSequence& sequence) {
  ClearCounts counts;
  std::vector<GtTrackState> tracks(static_cast<std::size_t>(sequence.num_gt_ids));
  tracker::LinearAssignment solver;
  std::vector<int> partner_of_gt;  // per gt index in this timestep: result index or kNone
  std::vector<char> result_taken;
  std::vector<int> open_gt, open_results;
  std::vector<double> cost;
  std::vector<char> present(tracks.size(), 0);  // per gt id: in this timestep
  std::vector<int> present_before;              // gt ids of the previous timestep

  const int timesteps = static_cast<int>(sequence.gt.size());
  for (int t = 0; t < timesteps; ++t) {
    const TimestepBoxes& gt = sequence.gt[static_cast<std::size_t>(t)];
    const TimestepBoxes& results = sequence.results[static_cast<std::size_t>(t)];
    const int gt_count = static_cast<int>(gt.ids.size());
    const int result_count = static_cast<int>(results.ids.size());
    partner_of_gt.assign(static_cast<std::size_t>(gt_count), kNone);
    result_taken.assign(static_cast<std::size_t>(result_count), 0);

    // 1. Keep last frame's correspondences that are still valid.
    for (int g = 0; g < gt_count; ++g) {
      const int previous = tracks[static_cast<std::size_t>(gt.ids[g])].previous_partner;
      if (previous == kNone) continue;
      const int r = find_index(results.ids, previous);
      if (r == kNone) continue;
      if (1.0 - box_iou(gt.boxes[g], results.boxes[r]) <= kMaxDistance) {
        partner_of_gt[g] = r;
        result_taken[r] = 1;
      }
    }

    // 2. Optimal assignment of the rest (both lists in id order, as the devkit sorts them).
    open_gt.clear();
    open_results.clear();
    for (int g = 0; g < gt_count; ++g) {
      if (partner_of_gt[g] == kNone) open_gt.push_back(g);
    }
    for (int r = 0; r < result_count; ++r) {
      if (!result_taken[r]) open_results.push_back(r);
    }
    const int rows = static_cast<int>(open_gt.size());
    const int cols = static_cast<int>(open_results.size());
    if (rows > 0 && cols > 0) {
      // A forbidden pair costs more than any set of allowed ones: largest matching first.
      const double forbidden = 2.0 + std::min(rows, cols);
      cost.assign(static_cast<std::size_t>(rows) * cols, forbidden);
      int tie_breaker = 0;  // the devkit adds 1e-9 per allowed pair, in row-major order
      for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
          const double distance =
              1.0 - box_iou(gt.boxes[open_gt[i]], results.boxes[open_results[j]]);
          if (distance <= kMaxDistance) {
            cost[static_cast<std::size_t>(i) * cols + j] = distance + 1e-9 * tie_breaker++;
          }
        }
      }
      const auto& assignment = solver.solve(cost.data(), rows, cols);
      for (int i = 0; i < rows; ++i) {
        const int j = assignment[i];
        if (j == kNone || cost[static_cast<std::size_t>(i) * cols + j] >= forbidden) continue;
        partner_of_gt[open_gt[i]] = open_results[j];
      }
    }

    // 3. Count.
    int matches = 0;
    for (int g = 0; g < gt_count; ++g) {
      GtTrackState& track = tracks[static_cast<std::size_t>(gt.ids[g])];
      ++track.frames_present;
      track.last_timestep = t;
      const int r = partner_of_gt[g];
      if (r == kNone) continue;
      ++matches;
      const int partner = results.ids[r];
      counts.iou_sum += box_iou(gt.boxes[g], results.boxes[r]);
      if (track.present_previously && track.last_partner != kNone &&
          track.last_partner != partner) {
        ++counts.id_switches;
      }
      ++track.frames_tracked;
    }
    counts.true_positives += matches;
    counts.false_positives += result_count - matches;
    counts.false_negatives += gt_count - matches;
    counts.gt_detections += gt_count;

    // 4. Carry the state to the next timestep. A gt box absent now is untracked now. Only the ids
    // of this timestep and the previous one change: time grows with boxes, not with ids x frames.
    for (int g = 0; g < gt_count; ++g) {
      GtTrackState& track = tracks[static_cast<std::size_t>(gt.ids[g])];
      present[static_cast<std::size_t>(gt.ids[g])] = 1;
      const int r = partner_of_gt[g];
      const bool tracked = r != kNone;
      // A fragmentation: tracked again after an interruption (the devkit's 1 -> 0 transitions
      // between the first and last tracked frames).
      if (tracked && track.ever_tracked && !track.tracked_previously) ++counts.fragmentations;
      track.tracked_previously = tracked;
      track.ever_tracked = track.ever_tracked || tracked;
      track.previous_partner = tracked ? results.ids[r] : kNone;
      if (tracked) track.last_partner = results.ids[r];
    }
    for (const int id : present_before) {
      GtTrackState& track = tracks[static_cast<std::size_t>(id)];
      if (present[static_cast<std::size_t>(id)]) continue;
      track.present_previously = false;
      track.tracked_previously = false;
      track.previous_partner = kNone;
    }
    present_before.clear();
    for (int g = 0; g < gt_count; ++g) {
      const auto id = static_cast<std::size_t>(gt.ids[g]);
      tracks[id].present_previously = true;
      present[id] = 0;
      present_before.push_back(gt.ids[g]);
    }
  }

  counts.frames = timesteps;
  counts.gt_tracks = sequence.num_gt_ids;
  for (const GtTrackState& track : tracks) {
    if (track.frames_present == 0) continue;
    const double ratio = static_cast<double>(track.frames_tracked) / track.frames_present;
    if (ratio < 0.2) {
      ++counts.mostly_lost;
    } else if (sequence.last_result_timestep >= track.last_timestep && ratio <= 0.8) {
      ++counts.partly_tracked;
    } else if (ratio >= 0.8) {
      ++counts.mostly_tracked;
    }
  }
  return counts;
}

SequenceCounts count_all(const PreparedSequence& sequence) {
  SequenceCounts counts;
  counts.clear = count_clear(sequence);
  counts.identity = count_identity(sequence);
  counts.hota = count_hota(sequence);
  return counts;
}

}  // namespace rtmot::mot
