#pragma once
// The progress line of a long batch of runs (the study's cross-validation ran ~150 s in silence;
// `rtmot study` prints it every few seconds, apps/cmd_study.cpp).
#include <cstddef>
#include <string>

namespace rtmot::study {

/// "run 120 of 624 (19%) | ETA 2:05": the ETA from the pace so far (`elapsed_s` since the batch
/// started); no ETA before the first run or after the last.
std::string run_progress_line(std::size_t done, std::size_t total, double elapsed_s);

}  // namespace rtmot::study
