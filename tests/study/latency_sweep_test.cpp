// The latency sweep: the frames it tracks are those the real pipeline processes in `simulated`
// playback (run here, in process, with the replay detector and --mot-results), and its tables
// are deterministic and agree with the plain study where no frame is skipped.
#include "study/latency_sweep.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>

#include "motio/processed_frames.hpp"
#include "pipeline/pipeline.hpp"
#include "runner/run_config.hpp"
#include "runner/run_setup.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"

namespace rtmot::study {
namespace {

namespace fs = std::filesystem;

// The frames `rtmot run --playback simulated --latency-ms L --mot-results` lists for `sequence`.
std::vector<int> frames_the_pipeline_processes(const fs::path& sequence, double latency_ms) {
  const fs::path out = fs::temp_directory_path() / ("rtmot-latency-" + std::to_string(::getpid()));
  fs::remove_all(out);
  runner::RunConfig config = runner::default_run_config();
  config.source.uri = "mot-seq://" + sequence.string();
  config.detector.kind = runner::DetectorKind::replay;
  config.detector.det_file = (sequence / "det/det.txt").string();
  config.playback.mode = pipeline::PlaybackMode::simulated;
  config.playback.latency_ms = latency_ms;
  config.output.mot_results = out.string();
  config.stats_interval_s = 0.0;
  runner::validate(config);
  auto inputs = runner::make_inputs(config);
  runner::RunOutputs outputs = runner::make_outputs(config, inputs);
  pipeline::Pipeline pipeline(std::move(inputs), runner::make_detector(config),
                              std::move(outputs.consumers), runner::make_options(config));
  const std::atomic<bool> stop{false};
  pipeline.run(stop);
  const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
  auto frames = motio::read_processed_frames(out / (info.name + ".frames"), info.length);
  fs::remove_all(out);
  return frames;
}

TEST(LatencySweep, TracksTheFramesThePipelineProcesses) {
  for (const auto& [name, latency_ms] : std::vector<std::pair<std::string, double>>{
           {"TUD-Stadtmitte", 130.0}, {"KITTI-17", 250.0}, {"ETH-Sunnyday", 100.0}}) {
    const fs::path sequence = test::shared_path("data/mot15-train/" + name);
    RTMOT_REQUIRE_FILE(sequence / "det/det.txt");
    const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
    const std::vector<int> study = pipeline_frames(info, {latency_ms, 0.0}, 1);
    EXPECT_EQ(study, frames_the_pipeline_processes(sequence, latency_ms)) << name;
    // The detector is slower than the camera: frames are skipped, the last one never.
    EXPECT_LT(study.size(), static_cast<std::size_t>(info.length)) << name;
    EXPECT_EQ(study.back(), info.length) << name;
  }
}

TEST(LatencySweep, JitterIsSeededAndChangesTheFrames) {
  const fs::path sequence = test::shared_path("data/mot15-train/KITTI-17");
  RTMOT_REQUIRE_FILE(sequence / "seqinfo.ini");
  const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
  const DetectorLatency jittered{250.0, 0.5};
  EXPECT_EQ(pipeline_frames(info, jittered, 7), pipeline_frames(info, jittered, 7));
  EXPECT_NE(pipeline_frames(info, jittered, 7), pipeline_frames(info, jittered, 8));
  EXPECT_NE(pipeline_frames(info, jittered, 7), pipeline_frames(info, {250.0, 0.0}, 7));
  // In frame periods: 5 takes every 5th frame and 10 every 10th, at this sequence's 10 fps.
  const std::vector<int> fifth = pipeline_frames(info, {0.0, 0.0, 5.0}, 1);
  ASSERT_GT(fifth.size(), 3U);
  for (std::size_t i = 1; i + 1 < fifth.size(); ++i) EXPECT_EQ(fifth[i] - fifth[i - 1], 5);
  const std::vector<int> tenth = pipeline_frames(info, {0.0, 0.0, 10.0}, 1);
  for (std::size_t i = 1; i + 1 < tenth.size(); ++i) EXPECT_EQ(tenth[i] - tenth[i - 1], 10);
  EXPECT_EQ(latency_label({0.0, 0.0, 5.0}), "5 frames");
  // A detector faster than the camera takes every frame.
  EXPECT_EQ(pipeline_frames(info, {0.0, 0.0}, 1).size(), static_cast<std::size_t>(info.length));
  EXPECT_EQ(pipeline_frames(info, {99.0, 0.0}, 1).size(), static_cast<std::size_t>(info.length));
}

TEST(LatencySweep, TablesAreDeterministicAndMatchTheStudyWithoutSkipping) {
  const auto dataset =
      load_study_dataset(test::shared_path("data/mot15-train/TUD-Campus").string());
  ASSERT_EQ(dataset.size(), 1U);
  const std::vector<DetectorLatency> latencies = {{0.0, 0.0}, {200.0, 0.0}, {200.0, 0.5}};
  const auto once =
      run_latency_sweep(dataset, {"rtmot", "sort"}, {StudyInput::detections}, latencies, 2);
  const auto again =
      run_latency_sweep(dataset, {"rtmot", "sort"}, {StudyInput::detections}, latencies, 1);
  ASSERT_EQ(once.size(), 2U);
  for (std::size_t t = 0; t < once.size(); ++t) {
    EXPECT_EQ(format_latency_csv(once[t]), format_latency_csv(again[t]));
    const auto& rows = once[t].rows;
    ASSERT_EQ(rows.size(), 3U);
    // No skipping: the study's own score at interval 1, on both scopes.
    const mot::Metrics every_frame = track_and_score(dataset, StudyInput::detections,
                                                     *tracker::find_preset(once[t].preset), 1, {});
    EXPECT_DOUBLE_EQ(rows[0].processed.mota, every_frame.mota);
    EXPECT_DOUBLE_EQ(rows[0].full_rate.mota, every_frame.mota);
    // ... and nothing to predict.
    EXPECT_EQ(rows[0].frames_predicted, 0);
    EXPECT_DOUBLE_EQ(rows[0].full_rate_output.mota, every_frame.mota);
    EXPECT_EQ(rows[0].frames_processed, 71);
    // 200 ms at 25 fps: every 5th frame, as the study's interval 5.
    const mot::Metrics fifth = track_and_score(dataset, StudyInput::detections,
                                               *tracker::find_preset(once[t].preset), 5, {});
    EXPECT_EQ(rows[1].frames_processed, 15);
    EXPECT_DOUBLE_EQ(rows[1].processed.mota, fifth.mota);
    EXPECT_DOUBLE_EQ(rows[1].processed.idf1, fifth.idf1);
    // At the full rate the skipped frames' boxes are misses.
    EXPECT_LT(rows[1].full_rate.mota, rows[1].processed.mota - 20.0);
    EXPECT_GT(rows[1].full_rate.false_negatives, rows[1].processed.false_negatives);
    // The full-rate output fills the 56 skipped frames with predictions: fewer misses.
    EXPECT_EQ(rows[1].frames_predicted, 71 - 15);
    EXPECT_LT(rows[1].full_rate_output.false_negatives, rows[1].full_rate.false_negatives);
  }
}

}  // namespace
}  // namespace rtmot::study
