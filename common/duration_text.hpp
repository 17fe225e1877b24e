#pragma once
// How a remaining time is written in progress lines ("ETA 2:05"): `rtmot run`'s periodic line
// (pipeline/progress_line.cpp) and `rtmot study`'s (study/run_progress.hpp).
#include <string>

namespace rtmot {

/// `seconds` rounded to whole seconds as "m:ss" (minutes beyond 59 stay minutes: "75:00").
/// Negative or not finite: "0:00".
std::string minutes_seconds(double seconds);

}  // namespace rtmot
