#pragma once
// Runs a study: every configuration x input x interval, tracked and scored, over a small thread
// pool (the Tracker itself stays single-threaded; each run owns its own).
#include <atomic>
#include <functional>
#include <vector>

#include "mot/metrics.hpp"
#include "study/study_dataset.hpp"
#include "study/study_plan.hpp"

namespace rtmot::study {

struct StudyRow {
  int interval{1};
  mot::Metrics metrics;
};

/// One configuration on one input: a row per interval, in the order asked.
struct StudyTable {
  StudyConfiguration configuration;
  StudyInput input{StudyInput::detections};
  std::vector<StudyRow> rows;
};

/// Called after each finished run with (runs done, runs in all, its table, its interval), from
/// the worker threads: it must be thread-safe (spdlog is).
using StudyProgress =
    std::function<void(int done, int total, const StudyTable& table, int interval)>;

/// `stop` (may be null): once it is true no further run starts; the tables come back with the rows
/// not run left empty (the caller discards them).
std::vector<StudyTable> run_study(const std::vector<LoadedSequence>& dataset,
                                  const std::vector<StudyConfiguration>& configurations,
                                  const std::vector<StudyInput>& inputs,
                                  const std::vector<int>& intervals, int jobs,
                                  const StudyProgress& progress = {},
                                  const std::atomic<bool>* stop = nullptr);

}  // namespace rtmot::study
