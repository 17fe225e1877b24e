#pragma once
// How alike a track's predicted box and a detection are; larger is more similar for every kind.
#include "tracker/box.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

/// Intersection over union, in [0, 1].
float iou_affinity(const Box& track, const Box& detection);

/// Sanchez-Matilla et al.'s linear cost (centre distance times area difference), inverted as in
/// C++SORT: (image diagonal / centre distance) * (image area / |area difference|). Capped at
/// kMaxLinearAffinity so that identical boxes stay finite for the assignment.
double linear_affinity(const Box& track, const Box& detection, float image_width,
                       float image_height);
inline constexpr double kMaxLinearAffinity = 1e12;

/// Yu et al.'s motion and shape affinity without the appearance term, in (0, 1]:
/// exp(-0.5((dx/w)^2 + (dy/h)^2)) * exp(-1.5(|dh|/(h+h') + |dw|/(w+w'))), w and h of the track.
double exponential_affinity(const Box& track, const Box& detection);

/// The affinity the config selects. With `time_widened_gate`, `gate_frames` (nominal frames since
/// the track's last match or since the previous processed frame, per `gate_clock`; >= 1 after a
/// prediction) loosens the comparison: IoU is taken on boxes enlarged with that time (as C-BIoU),
/// the other kinds are scaled up by it. `noise_margin` (the stream's box noise) is a floor under
/// that margin; both stay within max_gate_margin.
double affinity(const TrackerConfig& config, const Box& track, const Box& detection,
                double gate_frames, float noise_margin = 0.F);

/// The enlargement margin (fraction of the size per side) after `gate_frames` frames, at most
/// `max_margin`.
float widened_gate_margin(double gate_frames, double max_margin);

}  // namespace rtmot::tracker
