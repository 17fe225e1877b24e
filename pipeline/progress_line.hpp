#pragma once
// The periodic line of a one-source run (the sink stage writes it every stats_interval_s): position
// ("frame N of TOTAL (P%)" for a file of known length or a --max-frames run), rate, capture->sent
// latency over the interval, counts, and the ETA at the source's pace.
#include <cstdint>
#include <string>

namespace rtmot::pipeline {

/// The line's text (without the timestamp spdlog adds). `total_frames` 0: unknown (live, or a
/// stream without a length): no percentage, no ETA.
std::string progress_line(std::int64_t frame, std::int64_t total_frames, double fps,
                          double source_frames_per_s, double p50_ms, double p95_ms,
                          std::uint64_t processed, std::uint64_t skipped);

}  // namespace rtmot::pipeline
