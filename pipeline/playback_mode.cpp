#include "pipeline/playback_mode.hpp"

#include "tracker/enum_names.hpp"

namespace rtmot::pipeline {
namespace {

constexpr auto playback_mode_names = tracker::make_enum_names<PlaybackMode>(
    std::pair{PlaybackMode::every_frame, std::string_view{"every-frame"}},
    std::pair{PlaybackMode::realtime, std::string_view{"realtime"}},
    std::pair{PlaybackMode::simulated, std::string_view{"simulated"}});

}  // namespace

std::string to_string(PlaybackMode mode) {
  return std::string(playback_mode_names.name(mode));
}

std::optional<PlaybackMode> parse_playback_mode(const std::string& text) {
  return playback_mode_names.parse(text);
}

std::string playback_mode_alternatives() {
  return playback_mode_names.alternatives();
}

}  // namespace rtmot::pipeline
