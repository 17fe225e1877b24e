// The track's life stage as Tracker::track_table() shows it: the persistent stages and the
// transitions between them under SORT's and ByteTrack's rules, on a walker that is missed.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "scene.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;

constexpr double kRate = 30.0;

// The stage of track `id` after each frame ("-" when it is not in the table), for a walker moving
// 2 px a frame from frame 4 on (after SORT's warm-up), absent in the frames of `missing`.
std::vector<std::string> stages(const TrackerConfig& config, int frames,
                                const std::vector<int>& missing, int id = 1) {
  Tracker tracker(config);
  std::vector<std::string> out;
  for (int f = 1; f <= frames; ++f) {
    std::vector<Detection> detections;
    const bool absent = f <= 3 || std::find(missing.begin(), missing.end(), f) != missing.end();
    if (!absent) detections.push_back(detection(100.F + 2.F * f, 200.F));
    const auto& reports = tracker.update(detections, f / kRate);
    const auto& table = tracker.track_table();
    const auto it =
        std::find_if(table.begin(), table.end(), [id](const TrackReport& r) { return r.id == id; });
    out.emplace_back(it == table.end() ? "-" : kTrackStageNames.name(it->stage));
    // update() reports exactly the confirmed tracks of the table.
    for (const auto& row : table) {
      const bool reported = std::any_of(reports.begin(), reports.end(),
                                        [&](const TrackReport& r) { return r.id == row.id; });
      EXPECT_EQ(reported, row.stage == TrackStage::confirmed) << "frame " << f << " id " << row.id;
    }
    for (const auto& report : reports) EXPECT_EQ(report.stage, TrackStage::confirmed);
  }
  return out;
}

TrackerConfig sort_with_memory() {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 2;
  config.min_hits = 2;
  return config;
}

using Stages = std::vector<std::string>;

TEST(TrackStage, SortRulesLoseAConfirmedTrackAtAMissAndMakeItProveItselfAgain) {
  // Born at 4, confirmed at 6 (two matches after its birth), missed at 8 (lost, coasting), found
  // at 9 (still lost: two new matches needed), confirmed again at 10.
  const Stages expected = {"-",         "-",    "-",    "tentative", "tentative", "confirmed",
                           "confirmed", "lost", "lost", "confirmed", "confirmed"};
  EXPECT_EQ(stages(sort_with_memory(), 11, {8}), expected);
}

TEST(TrackStage, ATrackMissedLongerThanMaxAgeIsRemoved) {
  // Confirmed at 6, missed from 8 on: lost at 8 and 9, gone after more than max_age (2) frames.
  const Stages got = stages(sort_with_memory(), 11, {8, 9, 10, 11});
  EXPECT_EQ(got[5], "confirmed");
  EXPECT_EQ(got[7], "lost");
  EXPECT_EQ(got[8], "lost");
  EXPECT_EQ(got[9], "-");
  EXPECT_EQ(got[10], "-");
}

TEST(TrackStage, ATentativeTrackThatMissesStaysTentative) {
  // Born at 4, missed at 5: never confirmed, so not lost but still tentative while it coasts.
  const Stages got = stages(sort_with_memory(), 6, {5});
  EXPECT_EQ(got[3], "tentative");
  EXPECT_EQ(got[4], "tentative");
}

TEST(TrackStage, ByteTrackRulesKeepConfirmationAndRemoveAnUnprovenTrackAtItsFirstMiss) {
  const auto bytetrack = *find_preset("bytetrack");
  // Confirmed at its second match (5), lost at the miss (7), confirmed at once when found (8).
  const Stages kept = stages(bytetrack, 8, {7});
  const Stages expected = {"-",         "-",         "-",    "tentative",
                           "confirmed", "confirmed", "lost", "confirmed"};
  EXPECT_EQ(kept, expected);
  // A newborn missed at once is removed, not lost.
  const Stages dying = stages(bytetrack, 6, {5});
  EXPECT_EQ(dying[3], "tentative");
  EXPECT_EQ(dying[4], "-");
}

}  // namespace
}  // namespace rtmot::tracker
