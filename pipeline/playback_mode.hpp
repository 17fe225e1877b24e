#pragma once
// How the capture stage releases recorded frames to the detector (docs/architecture.md).
#include <optional>
#include <string>

namespace rtmot::pipeline {

enum class PlaybackMode {
  every_frame,  // recordings: every frame is processed (the capture waits for the detector)
  realtime,     // recordings: frames are released at their pts; a slow detector skips frames
  simulated,    // recordings: deterministic skipping by a detector latency model (virtual clock)
};

std::string to_string(PlaybackMode mode);
/// "every-frame", "realtime" or "simulated"; nullopt otherwise.
std::optional<PlaybackMode> parse_playback_mode(const std::string& text);
/// "every-frame, realtime or simulated", for help texts and errors.
std::string playback_mode_alternatives();

}  // namespace rtmot::pipeline
