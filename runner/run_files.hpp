#pragma once
// Internal to runner/ (run_files.cpp, run_outputs.cpp): the check of every file a run touches.
#include "runner/run_config.hpp"

namespace rtmot::runner {

// Every file a run reads (the configuration, the replayed detections, the model and what comes
// with it, file and sequence sources) and every file it writes.
void check_run_files(const RunConfig& config);

}  // namespace rtmot::runner
