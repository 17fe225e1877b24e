// Scoring the frames a run processed: the <sequence>.frames list beside MOT results, eval's
// --processed-frames scope, and the sampled-results detection behind eval's warning.
#include "motio/processed_frames.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "mot/evaluation.hpp"
#include "motio/results_writer.hpp"
#include "motio/track_runner.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"

namespace rtmot::mot {
namespace {

namespace fs = std::filesystem;

// A fresh folder under the system's temporary one, removed at the end of the test.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(fs::temp_directory_path() / ("rtmot-" + name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

TEST(ProcessedFrames, ReadsBackWhatItWrites) {
  const ScratchDir dir("frames-roundtrip");
  const fs::path file = motio::processed_frames_file(dir.path(), "TUD-Campus");
  EXPECT_EQ(file.filename(), "TUD-Campus.frames");
  const std::vector<int> frames = {1, 2, 7, 30, 71};
  motio::write_processed_frames(file, frames);
  EXPECT_EQ(motio::read_processed_frames(file, 71), frames);
}

TEST(ProcessedFrames, BadListsNameFileAndLine) {
  const ScratchDir dir("frames-bad");
  const fs::path file = dir.path() / "s.frames";
  for (const auto& [text, line] : std::vector<std::pair<std::string, int>>{
           {"1\n5\n3\n", 3}, {"# c\n1\nx\n", 3}, {"1\n72\n", 2}, {"0\n", 1}, {"1\n1\n", 2}}) {
    write_text(file, text);
    try {
      motio::read_processed_frames(file, 71);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& error) {
      EXPECT_EQ(error.line(), line) << text << ": " << error.what();
      EXPECT_NE(error.file().find("s.frames"), std::string::npos);
    }
  }
}

// rtmot track at interval 5 on TUD-Campus, as files: results and the processed frames.
fs::path track_every_fifth(const ScratchDir& dir, const fs::path& sequence_dir) {
  motio::TrackOptions options;
  options.config = *tracker::find_preset("rtmot");
  options.interval = 5;
  const motio::TrackRun run = motio::track_sequence(sequence_dir, options);
  motio::write_results(dir.path() / (run.info.name + ".txt"), run.tracks);
  motio::write_processed_frames(motio::processed_frames_file(dir.path(), run.info.name),
                                run.processed_frames);
  return dir.path() / (run.info.name + ".txt");
}

TEST(ProcessedFrames, ScoringTheListedFramesEqualsScoringTheInterval) {
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence / "gt/gt.txt");
  const ScratchDir dir("frames-eval");
  const fs::path results = track_every_fifth(dir, sequence);
  const SequenceScore by_interval = evaluate_sequence(sequence, results, 5);
  const SequenceScore on_frames = evaluate_sequence_on_frames(
      sequence, results, motio::processed_frames_file(dir.path(), "TUD-Campus"));
  const SequenceScore every_frame = evaluate_sequence(sequence, results, 1);
  EXPECT_EQ(on_frames.counts.clear.frames, by_interval.counts.clear.frames);
  EXPECT_DOUBLE_EQ(on_frames.metrics.mota, by_interval.metrics.mota);
  EXPECT_DOUBLE_EQ(on_frames.metrics.idf1, by_interval.metrics.idf1);
  // At every frame the four frames in five it never saw are misses.
  EXPECT_LT(every_frame.metrics.mota, by_interval.metrics.mota - 20.0);
  // What eval's warning rests on.
  EXPECT_EQ(every_frame.results_every, 5);
  EXPECT_EQ(evaluate_sequence(sequence, sequence / "gt/gt.txt", 1).results_every, 1);
}

TEST(ProcessedFrames, TrackingListedFramesEqualsTrackingTheInterval) {
  // TrackOptions::frames (the latency sweep's: the frames a slow pipeline processes).
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence / "det/det.txt");
  motio::TrackOptions options;
  options.config = *tracker::find_preset("rtmot");
  options.interval = 5;
  const motio::TrackRun by_interval = motio::track_sequence(sequence, options);
  options.interval = 1;
  options.frames = by_interval.processed_frames;
  const motio::TrackRun listed = motio::track_sequence(sequence, options);
  EXPECT_EQ(listed.processed_frames, by_interval.processed_frames);
  ASSERT_EQ(listed.tracks.size(), by_interval.tracks.size());
  for (std::size_t i = 0; i < listed.tracks.size(); ++i) {
    EXPECT_EQ(listed.tracks[i].frame, by_interval.tracks[i].frame);
    EXPECT_EQ(listed.tracks[i].id, by_interval.tracks[i].id);
    EXPECT_EQ(listed.tracks[i].box.x, by_interval.tracks[i].box.x);
  }
  // A list that does not ascend, or leaves the sequence, is refused.
  for (const std::vector<int>& bad :
       {std::vector<int>{1, 3, 3}, std::vector<int>{0, 2}, std::vector<int>{1, 72}}) {
    options.frames = bad;
    EXPECT_THROW(motio::track_sequence(sequence, options), InputError);
  }
}

TEST(ProcessedFrames, AnIrregularListScoresOnlyItsFrames) {
  // A pipeline that skipped irregularly: the same results scored on frames 1..10 and 20..30 only
  // count the ground truth of those 21 frames.
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence / "gt/gt.txt");
  const ScratchDir dir("frames-irregular");
  std::vector<int> frames;
  for (int f = 1; f <= 10; ++f) frames.push_back(f);
  for (int f = 20; f <= 30; ++f) frames.push_back(f);
  motio::write_processed_frames(dir.path() / "list.frames", frames);
  const SequenceScore score =
      evaluate_sequence_on_frames(sequence, sequence / "gt/gt.txt", dir.path() / "list.frames");
  EXPECT_EQ(score.counts.clear.frames, 21);
  EXPECT_GT(score.metrics.mota, 99.0);  // the ground truth as results
}

TEST(ProcessedFrames, AMissingListIsNamed) {
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence / "gt/gt.txt");
  const ScratchDir dir("frames-missing");
  try {
    evaluate_sequence_on_frames(sequence, sequence / "gt/gt.txt", dir.path() / "none.frames");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(error.file().find("none.frames"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace rtmot::mot
