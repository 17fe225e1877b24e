#pragma once
// The one place `detector.tiles: auto` is decided (docs/tiling.md, "What auto chooses"): from the
// frame size, the playback mode and the detector's measured speed, with the reason for the log.
#include <cstddef>
#include <optional>
#include <string>

#include "detector/tile_layout.hpp"
#include "detector/tiling_detector.hpp"
#include "pipeline/playback_mode.hpp"
#include "runner/run_config.hpp"

namespace rtmot::runner {

/// The largest frame of a run's sources and how its frames come.
struct FrameShape {
  int width{0};
  int height{0};
  double fps{0.0};  // 0: unknown
  bool live{false};
};

/// What one frame costs the detector, measured at start on the run's own detector.
struct DetectorCost {
  double whole_ms{0.0};         // the frame alone
  double tiled_ms{0.0};         // the frame and its tiles, one batch
  bool tiled_estimated{false};  // tiled_ms is cpu_tiled_floor_ms(), not a measurement
};

struct TilingDecision {
  bool tiled{false};
  std::string why;  // for the log line
};

/// The TilingDetector's settings for a run's detector section (auto's grid rule included).
detector::TilingConfig tiling_config(const DetectorConfig& detector);

/// The tiles auto would cut a frame of this shape into (1 x 1: none).
detector::TileGrid automatic_tile_grid(const DetectorConfig& detector, const FrameShape& frame);

/// Whether the run's frames need a measurement before auto can decide: a frame large enough to tile
/// whose frames may be skipped when the detector is slow (not every-frame playback).
bool tiling_needs_measurement(const DetectorConfig& detector, pipeline::PlaybackMode playback,
                              const FrameShape& frame);

/// The least a batch of the frame and its tiles can cost a CPU engine, from the whole frame's
/// measured cost. On the CPU a batch of n images costs about n single passes (768x576, 3x2 tiles +
/// the whole frame, 2 threads: XNNPACK 222-237 ms against 29-31 ms alone, 7.1-8.2x), so the
/// batch need not be built and timed (2-3 s at start) where even this floor misses the frame
/// period. The floor is kept well under the measured ratio (0.6 of n passes): where it does not
/// rule tiles out, the batch is timed. Not for CUDA, where a batch costs little more than one.
double cpu_tiled_floor_ms(double whole_ms, std::size_t passes);

/// Whether the tiled batch must be timed before auto can decide: the frame period is known and a
/// CPU engine's floor (cpu_tiled_floor_ms) does not already miss it.
bool tiled_cost_needs_timing(const FrameShape& frame, double whole_ms, std::size_t passes,
                             bool cpu_engine);

/// The decision for a request of `detector.tiles` (auto, off or a grid); `cost` is needed only
/// where tiling_needs_measurement() said so.
TilingDecision decide_tiling(const DetectorConfig& detector, pipeline::PlaybackMode playback,
                             const FrameShape& frame, const std::optional<DetectorCost>& cost);

}  // namespace rtmot::runner
