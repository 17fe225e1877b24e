#pragma once
// The one place `detector.tiles: auto` is decided (docs/tiling.md, "What auto chooses"): from the
// frame size, the playback mode and the detector's measured speed, with the reason for the log.
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
  double whole_ms{0.0};  // the frame alone
  double tiled_ms{0.0};  // the frame and its tiles, one batch
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

/// The decision for a request of `detector.tiles` (auto, off or a grid); `cost` is needed only
/// where tiling_needs_measurement() said so.
TilingDecision decide_tiling(const DetectorConfig& detector, pipeline::PlaybackMode playback,
                             const FrameShape& frame, const std::optional<DetectorCost>& cost);

}  // namespace rtmot::runner
