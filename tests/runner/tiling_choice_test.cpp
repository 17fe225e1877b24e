// detector.tiles: what the setting reads, and what auto decides from the frame, the playback mode
// and the detector's measured cost (runner/tiling_choice.hpp).
#include "runner/tiling_choice.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "detector/tile_request.hpp"
#include "runner/run_config.hpp"

namespace rtmot::runner {
namespace {

using detector::TileMode;
using pipeline::PlaybackMode;

TEST(TileRequest, ReadsOffAutoAndGrids) {
  std::string problem;
  EXPECT_EQ(detector::parse_tile_request("off", problem)->mode, TileMode::off);
  EXPECT_EQ(detector::parse_tile_request("auto", problem)->mode, TileMode::automatic);
  const auto grid = detector::parse_tile_request("3x2", problem);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->mode, TileMode::grid);
  EXPECT_EQ(grid->columns, 3);
  EXPECT_EQ(grid->rows, 2);
  EXPECT_EQ(detector::tile_request_text(*grid), "3x2");
  EXPECT_EQ(detector::parse_tile_request("1x1", problem)->mode, TileMode::off);
  for (const char* bad : {"", "3x", "x2", "0x2", "9x1", "3x2x1", "3X2", " 3x2", "3x2 ", "-1x2",
                          "on", "2x99999999999"}) {
    problem.clear();
    EXPECT_FALSE(detector::parse_tile_request(bad, problem)) << bad;
    EXPECT_NE(problem.find("COLUMNSxROWS"), std::string::npos) << bad;
  }
}

DetectorConfig with_tiles(const std::string& text) {
  DetectorConfig config;
  std::string problem;
  config.tiles = *detector::parse_tile_request(text, problem);
  return config;
}

const FrameShape kHd{1920, 1080, 30.0, false};
const FrameShape kPets{768, 576, 7.0, false};
const FrameShape kVga{640, 480, 30.0, false};

TEST(TilingChoice, AutoLeavesAFrameTheNetworkSeesWellWhole) {
  const auto config = with_tiles("auto");
  EXPECT_FALSE(tiling_needs_measurement(config, PlaybackMode::realtime, kVga));
  const auto decision = decide_tiling(config, PlaybackMode::every_frame, kVga, std::nullopt);
  EXPECT_FALSE(decision.tiled);
  EXPECT_NE(decision.why.find("640x480"), std::string::npos) << decision.why;
  // PETS09-S2L1's 768 x 576 is cut (3 x 2 tiles of 300 x 320).
  EXPECT_TRUE(decide_tiling(config, PlaybackMode::every_frame, kPets, std::nullopt).tiled);
}

// The network's size is the model's (its description): a 600 px network sees PETS09-S2L1's frame
// whole, where the bundled 300 px one needs tiles.
TEST(TilingChoice, TilesFollowTheModelsInputSize) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("rtmot-tiling-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "large.model.yaml") << "layout: deltas\ninput:\n  size: 600\n";
  auto config = with_tiles("auto");
  config.model = (dir / "large.onnx").string();
  EXPECT_EQ(tiling_config(config).network_size, 600);
  const auto decision = decide_tiling(config, PlaybackMode::every_frame, kPets, std::nullopt);
  EXPECT_FALSE(decision.tiled);
  EXPECT_NE(decision.why.find("network's 600 px"), std::string::npos) << decision.why;
  EXPECT_EQ(tiling_config(with_tiles("auto")).network_size, 300);  // no description: bundled
  std::filesystem::remove_all(dir);
}

TEST(TilingChoice, AutoTilesALargeFrameWhenNoFrameCanBeSkipped) {
  const auto config = with_tiles("auto");
  EXPECT_FALSE(tiling_needs_measurement(config, PlaybackMode::every_frame, kHd));
  const auto decision = decide_tiling(config, PlaybackMode::every_frame, kHd, std::nullopt);
  EXPECT_TRUE(decision.tiled) << decision.why;
  EXPECT_NE(decision.why.find("every frame"), std::string::npos) << decision.why;
}

TEST(TilingChoice, AutoTilesALiveOrPacedFrameOnlyWhenTheTilesKeepThePace) {
  const auto config = with_tiles("auto");
  for (const auto& [playback, frame] :
       {std::pair{PlaybackMode::realtime, kHd}, std::pair{PlaybackMode::simulated, kHd},
        std::pair{PlaybackMode::every_frame, FrameShape{1920, 1080, 30.0, true}}}) {
    EXPECT_TRUE(tiling_needs_measurement(config, playback, frame));
    // 33.3 ms between frames: a GPU's 12 ms batch of tiles keeps it, a CPU's 300 ms does not.
    const auto fast = decide_tiling(config, playback, frame, DetectorCost{2.0, 12.0});
    EXPECT_TRUE(fast.tiled) << fast.why;
    const auto slow = decide_tiling(config, playback, frame, DetectorCost{45.0, 300.0});
    EXPECT_FALSE(slow.tiled) << slow.why;
    EXPECT_NE(slow.why.find("300.0 ms"), std::string::npos) << slow.why;
    EXPECT_FALSE(decide_tiling(config, playback, frame, std::nullopt).tiled);
  }
}

TEST(TilingChoice, ACpuBatchIsTimedOnlyWhereTheWholeFramesCostLeavesRoomForIt) {
  // kHd: 33.3 ms between frames, 9 passes (4x2 tiles + the whole frame).
  constexpr std::size_t passes = 9;
  // 30 ms a whole frame: 9 passes cannot cost under 0.6 x 9 x 30 = 162 ms on a CPU engine.
  EXPECT_DOUBLE_EQ(cpu_tiled_floor_ms(30.0, passes), 162.0);
  EXPECT_FALSE(tiled_cost_needs_timing(kHd, 30.0, passes, true));
  // 5 ms: 27 ms may fit the 33.3 ms, so the batch is built and timed; on CUDA it always is.
  EXPECT_TRUE(tiled_cost_needs_timing(kHd, 5.0, passes, true));
  EXPECT_TRUE(tiled_cost_needs_timing(kHd, 30.0, passes, false));
  // No frame period (a rate not known): nothing to fit, nothing timed.
  EXPECT_FALSE(tiled_cost_needs_timing(FrameShape{1920, 1080, 0.0, true}, 1.0, passes, false));
  // The floor decides none and the log says it is a floor, not a measurement.
  const auto decision = decide_tiling(with_tiles("auto"), PlaybackMode::realtime, kHd,
                                      DetectorCost{30.0, 162.0, true});
  EXPECT_FALSE(decision.tiled);
  EXPECT_NE(decision.why.find("at least 162.0 ms"), std::string::npos) << decision.why;
}

TEST(TilingChoice, AutoCutsNothingWhenTheFrameSizeIsNotKnownAtStart) {
  // A camera absent at start reports 0 x 0 (it reconnects later).
  const auto decision = decide_tiling(with_tiles("auto"), PlaybackMode::realtime,
                                      FrameShape{0, 0, 0.0, true}, std::nullopt);
  EXPECT_FALSE(decision.tiled);
  EXPECT_NE(decision.why.find("not known"), std::string::npos) << decision.why;
}

TEST(TilingChoice, AGridOrOffIsTakenAsAsked) {
  EXPECT_TRUE(decide_tiling(with_tiles("2x2"), PlaybackMode::realtime, kVga, std::nullopt).tiled);
  EXPECT_FALSE(
      decide_tiling(with_tiles("off"), PlaybackMode::every_frame, kHd, std::nullopt).tiled);
  EXPECT_FALSE(tiling_needs_measurement(with_tiles("3x2"), PlaybackMode::realtime, kHd));
  auto replay = with_tiles("auto");
  replay.kind = DetectorKind::replay;
  EXPECT_FALSE(decide_tiling(replay, PlaybackMode::every_frame, kHd, std::nullopt).tiled);
  EXPECT_FALSE(tiling_needs_measurement(replay, PlaybackMode::realtime, kHd));
}

}  // namespace
}  // namespace rtmot::runner
