#include "tracker/tracker_options.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "tracker/tracker_limits.hpp"

namespace rtmot::tracker {
namespace {

// Text, not YAML's or CLI11's typed conversions: the same spelling is then accepted everywhere,
// and ".nan", "1e6" for a count or "2147483647" tracks are refused by the range, not converted.
template <typename Int>
bool parse_integer(std::string_view text, Int low, Int high, Int& out) {
  Int value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return false;
  if (value < low || value > high) return false;
  out = value;
  return true;
}

bool parse_real(std::string_view text, double& out) {
  // std::from_chars for floating point needs g++ 11 (Jetson has 9); strtod on a copy is portable.
  const std::string copy(text);
  if (copy.empty() || std::isspace(static_cast<unsigned char>(copy.front()))) return false;
  char* end = nullptr;
  const double value = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size() || !std::isfinite(value)) return false;
  out = value;
  return true;
}

bool parse_flag(std::string_view text, bool& out) {
  // YAML 1.1's spellings, as yaml-cpp reads booleans, so existing configurations keep working.
  for (const std::string_view yes : {"true", "True", "TRUE", "yes", "on"}) {
    if (text == yes) return out = true, true;
  }
  for (const std::string_view no : {"false", "False", "FALSE", "no", "off"}) {
    if (text == no) return out = false, true;
  }
  return false;
}

std::string number_text(double value) {
  std::string text = std::to_string(value);
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text.pop_back();
  return text;
}

template <typename Int>
TrackerOption integer(std::string name, std::string doc, Int TrackerConfig::*member, Int low,
                      Int high) {
  return {
      std::move(name), std::move(doc),
      "an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]",
      [=](TrackerConfig& c, std::string_view t) { return parse_integer(t, low, high, c.*member); }};
}

// A number in [low, high], or in (low, high] when `open_low` (a rate or a size).
template <typename Real>
TrackerOption real(std::string name, std::string doc, Real TrackerConfig::*member, double low,
                   double high, bool open_low = false) {
  const bool unbounded = high >= std::numeric_limits<float>::max();
  std::string expected = unbounded && low <= -high ? std::string("a finite number")
                         : unbounded               ? "a finite number >= " + number_text(low)
                                     : "a number in " + std::string(open_low ? "(" : "[") +
                                           number_text(low) + ", " + number_text(high) + "]";
  return {std::move(name), std::move(doc), std::move(expected),
          [=](TrackerConfig& c, std::string_view t) {
            double value = 0.0;
            if (!parse_real(t, value) || value > high || value < low || (open_low && value == low))
              return false;
            c.*member = static_cast<Real>(value);
            return true;
          }};
}

TrackerOption flag(std::string name, std::string doc, bool TrackerConfig::*member) {
  return {std::move(name), std::move(doc), "true or false",
          [=](TrackerConfig& c, std::string_view t) { return parse_flag(t, c.*member); }};
}

template <typename Enum, typename Names>
TrackerOption named(std::string name, std::string doc, Enum TrackerConfig::*member,
                    const Names& names) {
  return {std::move(name), std::move(doc), names.alternatives(),
          [=](TrackerConfig& c, std::string_view t) {
            const auto value = names.parse(t);
            if (value) c.*member = *value;
            return value.has_value();
          }};
}

TrackerOption affinity_option() {
  TrackerOption option =
      named("affinity", "track-detection similarity (sets its usual affinity_threshold)",
            &TrackerConfig::affinity, kAffinityNames);
  option.set = [](TrackerConfig& c, std::string_view t) {
    const auto value = kAffinityNames.parse(t);
    if (!value) return false;
    c.affinity = *value;
    c.affinity_threshold = default_threshold(c.affinity);
    return true;
  };
  return option;
}

using C = TrackerConfig;
using limits::kMaxCapacity;
using limits::kMaxFrames;

std::vector<TrackerOption> make_table() {
  constexpr double kHuge = std::numeric_limits<float>::max();
  return {
      named("predictor", "motion model", &C::predictor, kPredictorNames),
      affinity_option(),
      real("affinity_threshold", "minimum affinity for a match", &C::affinity_threshold, 0.0,
           kHuge),
      real("detection_threshold", "absolute score cut: detections below it are low (any scale)",
           &C::detection_threshold, -kHuge, kHuge),
      real("score_range_cut",
           "relative score cut: detections below this fraction of the recent 1st..99th percentile "
           "score range are low",
           &C::score_range_cut, 0.0, limits::kMaxScoreQuantile),
      real("score_range_cap",
           "no point of that range (the split, strong births) lies above this quantile of the "
           "recent scores, whatever their shape (0: no cap)",
           &C::score_range_cap, 0.0, limits::kMaxScoreQuantile),
      real("score_range_cap_below",
           "the cap engages only while its quantile lies below this fraction of the range: on a "
           "floor-heavy shape (1: always)",
           &C::score_range_cap_below, 0.0, 1.0),
      integer("max_age", "nominal frames a track survives without a match", &C::max_age, 0,
              kMaxFrames),
      integer("min_hits", "consecutive matches before a track is reported", &C::min_hits, 0,
              kMaxFrames),
      named("time_step", "predict one step per update, or by the real time elapsed", &C::time_step,
            kTimeStepNames),
      real("frame_rate", "nominal frame rate for elapsed steps (default: the source's)",
           &C::frame_rate, 0.0, limits::kMaxFrameRate, true),
      real("image_width", "image width for the linear affinity (default: the source's)",
           &C::image_width, 0.0, limits::kMaxImageSide, true),
      real("image_height", "image height for the linear affinity (default: the source's)",
           &C::image_height, 0.0, limits::kMaxImageSide, true),
      flag("second_round",
           "ByteTrack: detections below the score cuts (and >= low_score) only continue tracks, "
           "in a second round",
           &C::second_round),
      real("low_score", "lowest score the second round uses (absolute)", &C::low_score, -kHuge,
           kHuge),
      flag("observation_centric_reupdate",
           "OC-SORT: re-update a found-again track along a virtual trajectory",
           &C::observation_centric_reupdate),
      flag("time_widened_gate", "widen the gate with the time since a track's last match",
           &C::time_widened_gate),
      named("gate_clock",
            "what widens the gate: the time since the track's last match, or the time between "
            "processed frames",
            &C::gate_clock, kGateClockNames),
      flag("confirmed_tracks_first",
           "ByteTrack's order: tracks not yet confirmed only get the detections the confirmed "
           "ones leave",
           &C::confirmed_tracks_first),
      flag("confirm_by_duration",
           "also report a track once its run of matches lasts min_hits nominal frames",
           &C::confirm_by_duration),
      integer("min_coast_updates", "a track survives at least this many updates without a match",
              &C::min_coast_updates, 0, kMaxFrames),
      integer("duration_min_hits", "matches a run needs before confirm_by_duration may confirm it",
              &C::duration_min_hits, 1, kMaxFrames),
      flag("keep_confirmation",
           "a track once confirmed is reported again at its first match after a miss (ByteTrack)",
           &C::keep_confirmation),
      flag("tentative_dies_on_miss",
           "a track never confirmed is deleted at its first update without a match (ByteTrack)",
           &C::tentative_dies_on_miss),
      flag("second_round_recent_only",
           "the second round continues only confirmed tracks matched in the previous update "
           "(ByteTrack)",
           &C::second_round_recent_only),
      real("birth_threshold",
           "only detections scoring at least this (absolute) start tracks (any scale)",
           &C::birth_threshold, -kHuge, kHuge),
      real("strong_birth_range_cut",
           "a track born above this fraction of the recent score range is reported from its "
           "second detection; weaker births need min_hits (0: off)",
           &C::strong_birth_range_cut, 0.0, limits::kMaxScoreQuantile),
      real("second_round_threshold", "minimum affinity in the second round (0: affinity_threshold)",
           &C::second_round_threshold, 0.0, kHuge),
      real("max_gate_margin", "largest margin (of the box size per side) of the widened gate",
           &C::max_gate_margin, 0.0, limits::kMaxGateMargin),
      real("noise_gate_factor",
           "widen the gate by this many times the stream's median box offset from the "
           "prediction (0: off)",
           &C::noise_gate_factor, 0.0, limits::kMaxNoiseGateFactor),
      real("distance_gate_per_frame",
           "a last round matches a coasting track to a leftover detection whose centre is within "
           "this many box sizes per nominal frame between processed frames (0: off)",
           &C::distance_gate_per_frame, 0.0, limits::kMaxDistanceGate),
      real("distance_gate_max", "the largest reach of that round, in box sizes",
           &C::distance_gate_max, 0.0, limits::kMaxDistanceGate),
      integer("particle_count", "particles per track (particle predictor)", &C::particle_count, 1,
              limits::kMaxParticles),
      integer<std::uint64_t>("seed", "random seed of the particle predictor", &C::seed, 0,
                             UINT64_MAX),
      integer("max_tracks", "tracks preallocated; beyond them no new track starts", &C::max_tracks,
              1, kMaxCapacity),
      integer("max_detections", "detections a frame preallocated; beyond them the rest are ignored",
              &C::max_detections, 1, kMaxCapacity),
  };
}

}  // namespace

const std::vector<TrackerOption>& tracker_options() {
  static const std::vector<TrackerOption> table = make_table();
  return table;
}

const TrackerOption* find_tracker_option(std::string_view name) {
  for (const auto& option : tracker_options()) {
    if (option.name == name) return &option;
  }
  return nullptr;
}

std::string flag_name(const TrackerOption& option) {
  std::string flag = "--" + option.name;
  for (char& c : flag) {
    if (c == '_') c = '-';
  }
  return flag;
}

TrackerConfig with_options(
    TrackerConfig config,
    const std::vector<std::pair<std::string_view, std::string_view>>& values) {
  for (const auto& [name, text] : values) {
    const TrackerOption* option = find_tracker_option(name);
    if (option == nullptr) throw std::invalid_argument("tracker: no option " + std::string(name));
    if (!option->set(config, text)) {
      throw std::invalid_argument("tracker: " + std::string(name) + " = " + std::string(text) +
                                  ": expected " + option->expected);
    }
  }
  return config;
}

}  // namespace rtmot::tracker
