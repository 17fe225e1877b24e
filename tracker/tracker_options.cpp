#include "tracker/tracker_options.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "tracker/association.hpp"
#include "tracker/box_noise.hpp"
#include "tracker/score_cut.hpp"
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

// "none": an absolute score cut at the lowest float, which cuts nothing.
constexpr std::string_view kNoCut = "none";
constexpr float kLowest = std::numeric_limits<float>::lowest();

// The shortest text that reads back as `value` once cast to `Real`, as the setters read it: "0.3"
// for a float's 0.3 (not 0.300000011920929), "1920" (not 1.92e+03). snprintf and strtod read the
// same locale, so the text reads back wherever it was written.
template <typename Real>
std::string real_text(Real value) {
  std::array<char, 32> text{};
  if (std::abs(static_cast<double>(value)) < 1e15 && std::trunc(value) == value) {
    std::snprintf(text.data(), text.size(), "%.0f", static_cast<double>(value));
    return text.data();
  }
  for (int digits = 1; digits <= std::numeric_limits<double>::max_digits10; ++digits) {
    std::snprintf(text.data(), text.size(), "%.*g", digits, static_cast<double>(value));
    if (static_cast<Real>(std::strtod(text.data(), nullptr)) == value) break;
  }
  return text.data();
}

template <typename Int>
TrackerOption integer(std::string name, std::string doc, Int TrackerConfig::*member, Int low,
                      Int high) {
  return {
      std::move(name), std::move(doc),
      "an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]",
      [=](TrackerConfig& c, std::string_view t) { return parse_integer(t, low, high, c.*member); },
      [=](const TrackerConfig& c) { return std::to_string(c.*member); }};
}

// A number in [low, high], or in (low, high] when `open_low` (a rate or a size). Unbounded below
// (an absolute score, on any detector's scale), it may also be none: the lowest float.
template <typename Real>
TrackerOption real(std::string name, std::string doc, Real TrackerConfig::*member, double low,
                   double high, bool open_low = false) {
  const bool unbounded = high >= std::numeric_limits<float>::max();
  const bool may_be_none = low <= kLowest;
  std::string expected = unbounded && may_be_none
                             ? "a finite number, or " + std::string(kNoCut) + " for no cut"
                         : unbounded ? "a finite number >= " + real_text(low)
                                     : "a number in " + std::string(open_low ? "(" : "[") +
                                           real_text(low) + ", " + real_text(high) + "]";
  return {std::move(name), std::move(doc), std::move(expected),
          [=](TrackerConfig& c, std::string_view t) {
            if (may_be_none && t == kNoCut) {
              c.*member = static_cast<Real>(kLowest);
              return true;
            }
            double value = 0.0;
            if (!parse_real(t, value) || value > high || value < low || (open_low && value == low))
              return false;
            c.*member = static_cast<Real>(value);
            return true;
          },
          [=](const TrackerConfig& c) {
            const Real value = c.*member;
            return may_be_none && value <= static_cast<Real>(kLowest) ? std::string(kNoCut)
                                                                      : real_text(value);
          }};
}

TrackerOption flag(std::string name, std::string doc, bool TrackerConfig::*member) {
  return {std::move(name), std::move(doc), "true or false",
          [=](TrackerConfig& c, std::string_view t) { return parse_flag(t, c.*member); },
          [=](const TrackerConfig& c) { return std::string(c.*member ? "true" : "false"); }};
}

template <typename Enum, typename Names>
TrackerOption named(std::string name, std::string doc, Enum TrackerConfig::*member,
                    const Names& names) {
  return {std::move(name), std::move(doc), names.alternatives(),
          [=](TrackerConfig& c, std::string_view t) {
            const auto value = names.parse(t);
            if (value) c.*member = *value;
            return value.has_value();
          },
          [=](const TrackerConfig& c) { return std::string(names.name(c.*member)); }};
}

TrackerOption affinity_option() {
  std::string usual;
  for (const auto& [kind, kind_name] : kAffinityNames.entries()) {
    usual += (usual.empty() ? "" : ", ") + std::string(kind_name) + " " +
             real_text(default_threshold(kind));
  }
  TrackerOption option = named(
      "affinity", "track-detection similarity; sets its usual affinity_threshold (" + usual + ")",
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

// The docs are docs/config.md's tracker table (tests/runner/tracker_docs_test.cpp writes it from
// here) and --help's: everything a user needs to know of an option is here, once.
std::vector<TrackerOption> make_table() {
  constexpr double kHuge = std::numeric_limits<float>::max();
  const std::string score_window = std::to_string(kScoreWindow);
  return {
      named("predictor",
            "motion model: kalman (SORT's, on centre, area and ratio), kalman_xyah (DeepSORT's "
            "and ByteTrack's, on centre, aspect and height, noise proportional to the height), "
            "stationary or particle",
            &C::predictor, kPredictorNames),
      affinity_option(),
      real("affinity_threshold", "minimum affinity for a match, on the affinity's own scale",
           &C::affinity_threshold, 0.0, kHuge),
      real("detection_threshold",
           "absolute score cut on the detector's scale: detections below it are low",
           &C::detection_threshold, -kHuge, kHuge),
      real("score_range_cut",
           "relative score cut: detections below this fraction of the last " + score_window +
               " scores' 1st..99th percentile range are low (0: off)",
           &C::score_range_cut, 0.0, limits::kMaxScoreQuantile),
      real("score_range_cap",
           "no point of that range (the split, strong_birth_range_cut) lies above this quantile "
           "of the same recent scores (where score_range_cap_below engages it): on floor-heavy, "
           "long-tailed scores (margins, un-squashed network outputs) a fraction of the range "
           "lies far up the tail (0: no cap)",
           &C::score_range_cap, 0.0, limits::kMaxScoreQuantile),
      real("score_range_cap_below",
           "the cap engages only while its quantile lies below this fraction of the same range: "
           "on a floor-heavy shape (most scores near a floor under a long upper tail), not where "
           "false detections merely outnumber the true ones (1: whenever the cap is lower than a "
           "range point)",
           &C::score_range_cap_below, 0.0, 1.0),
      integer("max_age", "nominal frames a track survives without a match", &C::max_age, 0,
              kMaxFrames),
      integer("min_hits",
              "consecutive matches after the birth before a track is reported (1: from its "
              "second detection, ByteTrack's count); with confirm_by_duration a streak as long in "
              "time also confirms; every track is reported in the first min_hits frames (SORT's "
              "start-up; nominal frames with confirm_by_duration)",
              &C::min_hits, 0, kMaxFrames),
      named("time_step",
            "per_update: one prediction step per processed frame; elapsed: by the time between "
            "the frames' timestamps (right when frames are skipped)",
            &C::time_step, kTimeStepNames),
      real("frame_rate",
           "nominal frame rate, converting time into frame periods (rtmot run: the source's "
           "unless set; rtmot track: the sequence's)",
           &C::frame_rate, 0.0, limits::kMaxFrameRate, true),
      real("image_width",
           "image width for the linear affinity's normalisation (rtmot run: the source's unless "
           "set; rtmot track: the sequence's)",
           &C::image_width, 0.0, limits::kMaxImageSide, true),
      real("image_height",
           "image height for the linear affinity's normalisation (rtmot run: the source's unless "
           "set; rtmot track: the sequence's)",
           &C::image_height, 0.0, limits::kMaxImageSide, true),
      flag("second_round",
           "ByteTrack's second round: low detections (below the score cuts, at or above "
           "low_score) only continue tracks; false: they are dropped",
           &C::second_round),
      real("low_score", "lowest score the second round uses, absolute (none: every score)",
           &C::low_score, -kHuge, kHuge),
      flag("observation_centric_reupdate",
           "OC-SORT: re-update a found-again track along a virtual trajectory",
           &C::observation_centric_reupdate),
      flag("time_widened_gate",
           "widen the gate (IoU on enlarged boxes) with time, up to max_gate_margin",
           &C::time_widened_gate),
      named("gate_clock",
            "what widens the gate: since_match (the time since the track's own last match: a "
            "track lost at full rate gets a wide gate too) or frame_gap (the time between "
            "processed frames: at full rate the gate stays plain)",
            &C::gate_clock, kGateClockNames),
      flag("confirmed_tracks_first",
           "ByteTrack's order: tracks never confirmed only get the detections the confirmed ones "
           "leave",
           &C::confirmed_tracks_first),
      flag("confirm_by_duration",
           "also report a track once its run of matches lasts min_hits nominal frames",
           &C::confirm_by_duration),
      integer("min_coast_updates",
              "a track survives at least this many processed frames without a match",
              &C::min_coast_updates, 0, kMaxFrames),
      integer("duration_min_hits", "matches a run needs before confirm_by_duration may confirm it",
              &C::duration_min_hits, 1, kMaxFrames),
      flag("keep_confirmation",
           "a track once confirmed is reported again at its first match after missed frames "
           "(ByteTrack); false: it proves itself again with min_hits matches (SORT)",
           &C::keep_confirmation),
      flag("tentative_dies_on_miss",
           "a track never confirmed is deleted at its first processed frame without a match "
           "(ByteTrack, DeepSORT); false: it coasts for max_age like a confirmed one (SORT)",
           &C::tentative_dies_on_miss),
      flag("second_round_recent_only",
           "ByteTrack: the second round continues only confirmed tracks matched in the previous "
           "update (not tracks lost longer, not unconfirmed ones)",
           &C::second_round_recent_only),
      real("birth_threshold",
           "only detections at or above this absolute score start tracks, on the detector's "
           "scale (ByteTrack's: 0.6)",
           &C::birth_threshold, -kHuge, kHuge),
      real("strong_birth_range_cut",
           "a track born at or above this fraction of the recent score range is reported from "
           "its second detection in a row; one born weaker needs min_hits matches (no birth is "
           "refused; 0: off)",
           &C::strong_birth_range_cut, 0.0, limits::kMaxScoreQuantile),
      real("second_round_threshold",
           "minimum affinity in the second round (ByteTrack's: IoU 0.5; 0: affinity_threshold)",
           &C::second_round_threshold, 0.0, kHuge),
      real("max_gate_margin",
           "largest enlargement of the widened gate, as a fraction of the box per side",
           &C::max_gate_margin, 0.0, limits::kMaxGateMargin),
      real("noise_gate_factor",
           "the gate is also widened by this many times the stream's median box offset from the "
           "one-frame prediction (the detector's jitter as the stream shows it, measured on "
           "matches one nominal frame apart over the last " +
               std::to_string(kBoxNoiseWindow) + "), up to max_gate_margin (0: off)",
           &C::noise_gate_factor, 0.0, limits::kMaxNoiseGateFactor),
      real("distance_gate_per_frame",
           "a last association round for the tracks every other round left coasting: each may "
           "take a high-score detection no round took whose centre lies within this many of its "
           "predicted box's sizes (dx/w, dy/h) per nominal frame between the processed frames, "
           "heights within " +
               real_text(kDistanceRoundHeightRatio) +
               "x; the closer pairs win (docs/events.md, \"Where it fails and why\"; 0: off)",
           &C::distance_gate_per_frame, 0.0, limits::kMaxDistanceGate),
      real("distance_gate_max", "that round's largest reach, in box sizes", &C::distance_gate_max,
           0.0, limits::kMaxDistanceGate),
      real("appearance_gate",
           "where the detections carry an appearance (detector.appearance): a track and a "
           "detection that look further apart than this (Hellinger distance of their colour "
           "signatures) are never matched (1: no gate)",
           &C::appearance_gate, 0.0, 1.0),
      flag("appearance_gate_contested",
           "the appearance gate refuses only pairs whose detection or track has another pair the "
           "affinity allows; a pair alone on both sides is matched by its motion "
           "(docs/appearance.md: measured, in no preset)",
           &C::appearance_gate_contested),
      flag("appearance_gate_rival_alike",
           "with appearance_gate_contested: a contested pair is refused only when a rival pair of "
           "its detection or track lies within the gate; where no rival looks alike, motion "
           "decides (docs/appearance.md: measured, in no preset)",
           &C::appearance_gate_rival_alike),
      real("appearance_weight",
           "among the pairs the affinity allows, the assignment prefers affinity x (1 - this x "
           "the appearance distance) (0: appearance plays no part in the choice)",
           &C::appearance_weight, 0.0, 1.0),
      real("appearance_momentum",
           "a track's appearance keeps this share of itself at each match by a detection no "
           "other detection overlaps",
           &C::appearance_momentum, 0.0, 0.999),
      real("reid_gate",
           "re-identification: a track confirmed for the first time (born partly hidden: at its "
           "first clear sighting within 1 s of its birth, then within at most 0.4) takes the id "
           "of a lost or removed track of its class that looks at most this far from it "
           "(Hellinger distance), was last seen at most reid_max_gap_s before within a walker's "
           "reach, and that no other such track nearly matches (docs/appearance.md; 0: off)",
           &C::reid_gate, 0.0, 1.0),
      real("reid_max_gap_s", "the longest gap re-identification bridges, in seconds",
           &C::reid_max_gap_s, 0.0, 3600.0),
      real("handback_gate",
           "with re-identification on (reid_gate): a confirmed track matched to a clean "
           "detection further than this from its model gives it up to a confirmed track "
           "matched within the last second but not yet in this update that re-identification "
           "would judge its person's; the matched track coasts (docs/appearance.md: measured, "
           "in no preset; 0: off)",
           &C::handback_gate, 0.0, 1.0),
      real("observed_gate_frames",
           "where the pipeline followed a track in the image across the frames a slow detector "
           "skipped (detector.follow_image), its gate is widened as for at most this many "
           "nominal frames instead of the whole gap: the image replaced the motion model's guess "
           "(docs/full-rate.md: measured, in no preset; 0: off)",
           &C::observed_gate_frames, 0.0, static_cast<double>(limits::kMaxFrames)),
      flag("resolve_crossings",
           "with re-identification on (reid_gate): two confirmed tracks whose boxes overlapped "
           "trade ids when their first clear sightings after it each look like the other's model "
           "(docs/appearance.md: measured, in no preset)",
           &C::resolve_crossings),
      integer("particle_count",
              "particles per track (particle predictor); max_tracks x particle_count is at most " +
                  std::to_string(limits::kMaxParticleStorage),
              &C::particle_count, 1, limits::kMaxParticles),
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
