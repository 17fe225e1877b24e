#pragma once
// The largest values a TrackerConfig accepts: past them the up-front allocations (slots, particle
// buffers) stop being a few hundred MB at most. Shared by the option parsers and the Tracker's own
// check, so a value the parser accepts is never refused later.
namespace rtmot::tracker::limits {

inline constexpr int kMaxCapacity = 10000;                 // max_tracks, max_detections
inline constexpr int kMaxParticles = 100000;               // particle_count per track
inline constexpr long long kMaxParticleStorage = 4000000;  // max_tracks x particle_count
inline constexpr int kMaxFrames = 1000000;                 // max_age, min_hits, min_coast_updates
inline constexpr double kMaxFrameRate = 10000.0;
inline constexpr double kMaxImageSide = 100000.0;
// A cut that keeps 1% still tracks something.
inline constexpr double kMaxScoreQuantile = 0.99;
// A box eleven times its size matches anything.
inline constexpr double kMaxGateMargin = 5.0;
// A centre eleven box sizes away is anywhere in a crowd: the distance gate's largest reach.
inline constexpr double kMaxDistanceGate = 10.0;
// Past it any jitter asks for the whole max_gate_margin.
inline constexpr double kMaxNoiseGateFactor = 100.0;

}  // namespace rtmot::tracker::limits
