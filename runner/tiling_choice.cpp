#include "runner/tiling_choice.hpp"

#include <fmt/format.h>

#include "detector/model_description.hpp"

namespace rtmot::runner {
namespace {

// How much larger than the network's input a tile may be: a tile twice the network's size shows a
// person of 60 px as the network's smallest anchor (30 px of 300) sees best (docs/tiling.md).
constexpr float kMaxTileMagnification = 2.F;

// The SSD's input side, as its model describes it (docs/model.md).
int network_size(const DetectorConfig& detector) {
  return detector::read_model_description(detector.model).input_size;
}

// The share of n single passes that a batch of n costs a CPU engine at least (cpu_tiled_floor_ms).
constexpr double kCpuBatchFloor = 0.6;

bool skips_frames(pipeline::PlaybackMode playback, const FrameShape& frame) {
  return frame.live || playback != pipeline::PlaybackMode::every_frame;
}

double frame_period_ms(const FrameShape& frame) {
  return frame.fps > 0.0 ? 1000.0 / frame.fps : 0.0;
}

}  // namespace

detector::TilingConfig tiling_config(const DetectorConfig& detector) {
  detector::TilingConfig tiling;
  tiling.automatic = detector.tiles.mode == detector::TileMode::automatic;
  tiling.grid = {detector.tiles.columns, detector.tiles.rows, detector.tile_overlap};
  tiling.network_size = network_size(detector);
  tiling.max_magnification = kMaxTileMagnification;
  tiling.merge.tile_score_threshold = detector.tile_threshold;
  return tiling;
}

detector::TileGrid automatic_tile_grid(const DetectorConfig& detector, const FrameShape& frame) {
  return detector::automatic_grid(frame.width, frame.height, network_size(detector),
                                  kMaxTileMagnification, detector.tile_overlap);
}

bool tiling_needs_measurement(const DetectorConfig& detector, pipeline::PlaybackMode playback,
                              const FrameShape& frame) {
  return detector.kind == DetectorKind::ssd &&
         detector.tiles.mode == detector::TileMode::automatic &&
         automatic_tile_grid(detector, frame).tiled() && skips_frames(playback, frame);
}

double cpu_tiled_floor_ms(double whole_ms, std::size_t passes) {
  return kCpuBatchFloor * static_cast<double>(passes) * whole_ms;
}

bool tiled_cost_needs_timing(const FrameShape& frame, double whole_ms, std::size_t passes,
                             bool cpu_engine) {
  const double period_ms = frame_period_ms(frame);
  if (period_ms <= 0.0) return false;  // no period to fit: auto cuts no tiles
  return !cpu_engine || cpu_tiled_floor_ms(whole_ms, passes) <= period_ms;
}

TilingDecision decide_tiling(const DetectorConfig& detector, pipeline::PlaybackMode playback,
                             const FrameShape& frame, const std::optional<DetectorCost>& cost) {
  using detector::TileMode;
  if (detector.kind != DetectorKind::ssd) return {false, "tiles: off (a replayed detections file)"};
  switch (detector.tiles.mode) {
    case TileMode::off:
      return {false, "tiles: off (detector.tiles)"};
    case TileMode::grid:
      return {true, fmt::format("tiles: {}x{} (detector.tiles)", detector.tiles.columns,
                                detector.tiles.rows)};
    case TileMode::automatic:
      break;
  }
  if (frame.width <= 0 || frame.height <= 0) {
    return {false,
            "tiles: auto chose none: the frame size is not known at start (a source not up "
            "yet); set detector.tiles to cut a grid"};
  }
  const detector::TileGrid grid = automatic_tile_grid(detector, frame);
  if (!grid.tiled()) {
    return {false,
            fmt::format("tiles: auto chose none: a {}x{} frame is at most {:.0f} x the "
                        "network's {} px already",
                        frame.width, frame.height, kMaxTileMagnification, network_size(detector))};
  }
  const std::string grid_text =
      fmt::format("{}x{} tiles + the whole frame", grid.columns, grid.rows);
  if (!skips_frames(playback, frame)) {
    return {true, fmt::format("tiles: auto chose {} for a {}x{} frame: every frame is processed, "
                              "so detail costs time, not frames",
                              grid_text, frame.width, frame.height)};
  }
  if (!cost) return {false, "tiles: auto chose none: the detector's speed was not measured"};
  const double period_ms = frame_period_ms(frame);
  // The detector keeps the camera's pace with its tiles: tiling costs no frame that the whole
  // frame alone would have had (docs/tiling.md, "Where tiling pays").
  if (period_ms > 0.0 && !cost->tiled_estimated && cost->tiled_ms <= period_ms) {
    return {true, fmt::format("tiles: auto chose {} for a {}x{} frame: measured {:.1f} ms a frame "
                              "with them ({:.1f} without), within the {:.1f} ms between frames",
                              grid_text, frame.width, frame.height, cost->tiled_ms, cost->whole_ms,
                              period_ms)};
  }
  return {false, fmt::format(
                     "tiles: auto chose none for a {}x{} frame: {} would take {}{:.1f} ms a "
                     "frame ({:.1f} without), past the {:.1f} ms between frames: more "
                     "frames skipped",
                     frame.width, frame.height, grid_text, cost->tiled_estimated ? "at least " : "",
                     cost->tiled_ms, cost->whole_ms, period_ms)};
}

}  // namespace rtmot::runner
