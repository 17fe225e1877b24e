// The scorer on small hand-built cases whose answers can be worked out on paper.
#include "mot/scorer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/input_error.hpp"
#include "mot/metrics.hpp"
#include "mot/prepared_sequence.hpp"

namespace rtmot::mot {
namespace {

motio::MotRow row(int frame, int id, float x, float y = 0.F, float w = 10.F, float h = 20.F) {
  motio::MotRow r;
  r.frame = frame;
  r.id = id;
  r.box = {x, y, w, h};
  return r;
}

motio::MotRow gt_row(int frame, int id, float x, int class_id, float visibility = 1.F) {
  motio::MotRow r = row(frame, id, x);
  r.class_id = class_id;
  r.visibility = visibility;
  return r;
}

Metrics score(const std::vector<motio::MotRow>& gt, const std::vector<motio::MotRow>& results,
              int interval = 1) {
  PrepareOptions options;
  options.interval = interval;
  return summarize(count_all(prepare_sequence(gt, results, options)));
}

/// Two people walking apart over `frames` frames.
std::vector<motio::MotRow> two_walkers(int frames) {
  std::vector<motio::MotRow> rows;
  for (int f = 1; f <= frames; ++f) {
    rows.push_back(row(f, 1, 10.F * f));
    rows.push_back(row(f, 2, 500.F - 10.F * f));
  }
  return rows;
}

TEST(Scorer, PerfectTrackingScoresOneHundredEverywhere) {
  const auto gt = two_walkers(10);
  auto results = gt;
  for (auto& r : results) r.id += 40;  // ids need not be equal, only consistent
  const Metrics m = score(gt, results);
  EXPECT_DOUBLE_EQ(m.mota, 100.0);
  EXPECT_DOUBLE_EQ(m.motp, 100.0);
  EXPECT_DOUBLE_EQ(m.idf1, 100.0);
  EXPECT_DOUBLE_EQ(m.hota, 100.0);
  EXPECT_DOUBLE_EQ(m.deta, 100.0);
  EXPECT_DOUBLE_EQ(m.assa, 100.0);
  EXPECT_DOUBLE_EQ(m.loca, 100.0);
  EXPECT_EQ(m.mostly_tracked, 2);
  EXPECT_EQ(m.id_switches, 0);
  EXPECT_EQ(m.fragmentations, 0);
}

TEST(Scorer, OneTrackSplitInTwoHalvesAssociation) {
  // One person, 10 frames; the tracker calls them 1 for frames 1-5 and 2 for 6-10. Each id pair
  // shares 5 frames of a union of 10: every true positive has association 5 / 10.
  std::vector<motio::MotRow> gt;
  std::vector<motio::MotRow> results;
  for (int f = 1; f <= 10; ++f) {
    gt.push_back(row(f, 1, 10.F * f));
    results.push_back(row(f, f <= 5 ? 1 : 2, 10.F * f));
  }
  const Metrics m = score(gt, results);
  EXPECT_DOUBLE_EQ(m.deta, 100.0);
  EXPECT_DOUBLE_EQ(m.assa, 50.0);
  EXPECT_NEAR(m.hota, 100.0 * std::sqrt(0.5), 1e-9);
  EXPECT_DOUBLE_EQ(m.idf1, 50.0);  // IDTP 5, IDFP 5, IDFN 5
  EXPECT_EQ(m.id_switches, 1);
  EXPECT_DOUBLE_EQ(m.mota, 90.0);
}

TEST(Scorer, TwoTracksSwappingIdsHaveAThirdOfTheAssociation) {
  // Tracker ids swap between the two walkers after frame 5: each id pair shares 5 frames of a
  // union of 10 + 10 - 5 = 15.
  const auto gt = two_walkers(10);
  auto results = gt;
  for (auto& r : results) {
    if (r.frame > 5) r.id = 3 - r.id;
  }
  const Metrics m = score(gt, results);
  EXPECT_DOUBLE_EQ(m.deta, 100.0);
  EXPECT_NEAR(m.assa, 100.0 / 3.0, 1e-9);
  EXPECT_NEAR(m.hota, 100.0 * std::sqrt(1.0 / 3.0), 1e-9);
  EXPECT_EQ(m.id_switches, 2);
  EXPECT_DOUBLE_EQ(m.idf1, 50.0);
}

TEST(Scorer, HotaAveragesOverLocalisationThresholds) {
  // Results shifted by half a width: IoU = 5*20 / (2*200 - 100) = 1/3, a match for the 6 alphas
  // 0.05..0.30 only. DetA = AssA = HOTA = 6/19; LocA = (6 * 1/3 + 13 * 1) / 19 (TrackEval counts
  // LocA as 1 where nothing matched). CLEAR needs IoU 0.5: no match at all.
  std::vector<motio::MotRow> gt;
  std::vector<motio::MotRow> results;
  for (int f = 1; f <= 4; ++f) {
    gt.push_back(row(f, 1, 100.F));
    results.push_back(row(f, 1, 105.F));
  }
  const Metrics m = score(gt, results);
  EXPECT_NEAR(m.deta, 100.0 * 6 / 19, 1e-9);
  EXPECT_NEAR(m.assa, 100.0 * 6 / 19, 1e-9);
  EXPECT_NEAR(m.hota, 100.0 * 6 / 19, 1e-9);
  EXPECT_NEAR(m.loca, 100.0 * (6.0 / 3.0 + 13.0) / 19, 1e-9);
  EXPECT_EQ(m.false_positives, 4);
  EXPECT_EQ(m.false_negatives, 4);
  EXPECT_DOUBLE_EQ(m.mota, -100.0);
}

TEST(Scorer, PreviousCorrespondenceIsKeptOverABetterNewMatch) {
  // Frame 2: result 2 fits gt 1 better than result 1 does, but result 1 still overlaps enough
  // (IoU 2/3): the devkit keeps it, so there is no ID switch and result 2 is a false positive.
  const std::vector<motio::MotRow> gt = {row(1, 1, 100.F), row(2, 1, 100.F)};
  const std::vector<motio::MotRow> results = {row(1, 1, 100.F), row(2, 1, 102.F), row(2, 2, 100.F)};
  const Metrics m = score(gt, results);
  EXPECT_EQ(m.id_switches, 0);
  EXPECT_EQ(m.false_positives, 1);
}

TEST(Scorer, SwitchIsCountedOnlyIfTheGtBoxWasInThePreviousFrame) {
  // The devkit's rule (clearMOTMex): gt 1 is missing from frame 2's annotation and comes back
  // with another id in frame 3: no switch. The same without the gap is one switch.
  const std::vector<motio::MotRow> gt_with_gap = {row(1, 1, 100.F), row(3, 1, 100.F)};
  const std::vector<motio::MotRow> results = {row(1, 1, 100.F), row(3, 2, 100.F)};
  EXPECT_EQ(score(gt_with_gap, results).id_switches, 0);
  const std::vector<motio::MotRow> gt_without_gap = {row(1, 1, 100.F), row(2, 1, 100.F),
                                                     row(3, 1, 100.F)};
  EXPECT_EQ(score(gt_without_gap, results).id_switches, 1);
}

TEST(Scorer, FragmentationsAndCoverageClasses) {
  // gt 1: 10 frames, tracked in 1-3 and 6-10 (8/10 = 0.8: partly tracked, not > 0.8), one
  // fragmentation. gt 2: 10 frames, tracked in 1 only (0.1: mostly lost).
  std::vector<motio::MotRow> gt;
  std::vector<motio::MotRow> results;
  for (int f = 1; f <= 10; ++f) {
    gt.push_back(row(f, 1, 100.F));
    gt.push_back(row(f, 2, 400.F));
    if (f <= 3 || f >= 6) results.push_back(row(f, 1, 100.F));
  }
  results.push_back(row(1, 2, 400.F));
  const Metrics m = score(gt, results);
  EXPECT_EQ(m.fragmentations, 1);
  EXPECT_EQ(m.partly_tracked, 1);
  EXPECT_EQ(m.mostly_lost, 1);
  EXPECT_EQ(m.mostly_tracked, 0);
  EXPECT_EQ(m.false_negatives, 2 + 9);
}

TEST(Scorer, ZeroConfidenceGtIsIgnored) {
  std::vector<motio::MotRow> gt = {row(1, 1, 100.F), row(1, 2, 300.F)};
  gt[1].conf = 0.F;
  const Metrics m = score(gt, {row(1, 5, 100.F)});
  EXPECT_EQ(m.gt_tracks, 1);
  EXPECT_EQ(m.false_negatives, 0);
  EXPECT_DOUBLE_EQ(m.mota, 100.0);
}

TEST(Scorer, ResultsOnDistractorsAreRemovedAndOnlyPedestriansCount) {
  // MOT16/17 gt: a pedestrian, a static person (7, distractor) and a car (3, neither).
  const std::vector<motio::MotRow> gt = {gt_row(1, 1, 100.F, 1), gt_row(1, 2, 300.F, 7),
                                         gt_row(1, 3, 600.F, 3)};
  const std::vector<motio::MotRow> results = {row(1, 1, 100.F), row(1, 2, 300.F), row(1, 3, 600.F)};
  const Metrics m = score(gt, results);
  EXPECT_EQ(m.gt_tracks, 1);
  // The box on the static person is gone; the box on the car stays as a false positive.
  EXPECT_EQ(m.false_positives, 1);
  EXPECT_EQ(m.false_negatives, 0);
}

TEST(Scorer, IntervalScoresOnlyEveryNthFrame) {
  // Results only exist on frames 1, 4, 7, 10: with --interval 3 tracking is perfect.
  const auto gt = two_walkers(10);
  std::vector<motio::MotRow> results;
  for (const auto& r : gt) {
    if ((r.frame - 1) % 3 == 0) results.push_back(r);
  }
  const Metrics every = score(gt, results, 3);
  EXPECT_DOUBLE_EQ(every.mota, 100.0);
  EXPECT_DOUBLE_EQ(every.hota, 100.0);
  EXPECT_DOUBLE_EQ(every.false_alarms_per_frame, 0.0);
  const Metrics all = score(gt, results, 1);
  EXPECT_EQ(all.false_negatives, 12);
}

TEST(Scorer, ResultsAfterTheLastGtFrameAreDropped) {
  const Metrics m = score({row(1, 1, 100.F)}, {row(1, 1, 100.F), row(2, 1, 100.F)});
  EXPECT_EQ(m.false_positives, 0);
}

TEST(Scorer, DuplicateIdInAFrameIsAnInputError) {
  PrepareOptions options;
  options.results_file = "res.txt";
  try {
    prepare_sequence({row(1, 1, 100.F)}, {row(1, 4, 100.F), row(1, 4, 300.F)}, options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "res.txt");
    EXPECT_EQ(error.field(), "id");
  }
}

TEST(Scorer, PoolingSumsCounts) {
  SequenceCounts a = count_all(prepare_sequence(two_walkers(5), two_walkers(5), {}));
  SequenceCounts b = count_all(prepare_sequence(two_walkers(5), {}, {}));
  a += b;
  const Metrics pooled = summarize(a);
  EXPECT_DOUBLE_EQ(pooled.recall, 50.0);
  EXPECT_DOUBLE_EQ(pooled.idf1, 100.0 * 2 * 10 / (2 * 10 + 10));
  EXPECT_EQ(pooled.gt_tracks, 4);
}

}  // namespace
}  // namespace rtmot::mot
