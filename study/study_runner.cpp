#include "study/study_runner.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

namespace rtmot::study {

std::vector<StudyTable> run_study(const std::vector<LoadedSequence>& dataset,
                                  const std::vector<StudyConfiguration>& configurations,
                                  const std::vector<StudyInput>& inputs,
                                  const std::vector<int>& intervals, int jobs,
                                  const StudyProgress& progress, const std::atomic<bool>* stop) {
  std::vector<StudyTable> tables;
  for (const auto& configuration : configurations) {
    for (const StudyInput input : inputs) {
      StudyTable table{configuration, input, {}};
      for (const int interval : intervals) table.rows.push_back(StudyRow{interval, {}});
      tables.push_back(std::move(table));
    }
  }
  const int runs_per_table = static_cast<int>(intervals.size());
  const int total = static_cast<int>(tables.size()) * runs_per_table;

  // Each run writes only its own preallocated row, so the workers share nothing but the next
  // run's index (relaxed is enough: the rows are published by join()) and the done count.
  std::atomic<int> next{0};
  std::atomic<int> done{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    for (int run = next++; run < total; run = next++) {
      if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;
      StudyTable& table = tables[static_cast<std::size_t>(run / runs_per_table)];
      StudyRow& row = table.rows[static_cast<std::size_t>(run % runs_per_table)];
      try {
        row.metrics = track_and_score(dataset, table.input, table.configuration.config,
                                      row.interval, table.configuration.knobs);
        if (progress) progress(++done, total, table, row.interval);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = total;
      }
    }
  };
  std::vector<std::thread> workers;
  const int threads = std::clamp(jobs, 1, std::max(total, 1));
  for (int t = 1; t < threads; ++t) workers.emplace_back(work);
  work();
  for (auto& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  return tables;
}

}  // namespace rtmot::study
