#include "study/study_cv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "mot/metrics.hpp"
#include "mot/sequence_counts.hpp"

namespace rtmot::study {
namespace {

// counts[candidate][input][interval][sequence], every run once.
using Counts = std::vector<std::vector<std::vector<std::vector<mot::SequenceCounts>>>>;
// use[input][sequence]: which runs a score pools.
using Mask = std::vector<std::vector<bool>>;

Counts count_everything(const std::vector<LoadedSequence>& dataset,
                        const std::vector<StudyConfiguration>& candidates,
                        const std::vector<StudyInput>& inputs, const std::vector<int>& intervals,
                        int jobs, const std::atomic<bool>* stop, const RunProgress& progress) {
  const std::size_t n_s = dataset.size();
  const std::size_t n_i = intervals.size();
  const std::size_t n_d = inputs.size();
  Counts counts(candidates.size(), std::vector<std::vector<std::vector<mot::SequenceCounts>>>(
                                       n_d, std::vector<std::vector<mot::SequenceCounts>>(
                                                n_i, std::vector<mot::SequenceCounts>(n_s))));
  const std::size_t total = candidates.size() * n_d * n_i * n_s;
  // As run_study: each run writes only its own preallocated cell; join() publishes them.
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};  // only counted: the cells are published by join()
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    for (std::size_t run = next++; run < total; run = next++) {
      if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;
      const std::size_t s = run % n_s;
      const std::size_t i = (run / n_s) % n_i;
      const std::size_t d = (run / (n_s * n_i)) % n_d;
      const std::size_t c = run / (n_s * n_i * n_d);
      try {
        counts[c][d][i][s] = track_and_count(dataset[s], inputs[d], candidates[c].config,
                                             intervals[i], candidates[c].knobs);
        if (progress) progress(done.fetch_add(1, std::memory_order_relaxed) + 1, total);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = total;
      }
    }
  };
  std::vector<std::thread> workers;
  const int threads = std::max(1, std::min(jobs, static_cast<int>(total)));
  for (int t = 1; t < threads; ++t) workers.emplace_back(work);
  work();
  for (auto& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  return counts;
}

// The candidate's metrics per interval, pooled over the runs `use` marks.
std::vector<mot::Metrics> pooled(const Counts& counts, std::size_t candidate, const Mask& use) {
  const auto& by_input = counts[candidate];
  std::vector<mot::Metrics> by_interval;
  for (std::size_t i = 0; i < by_input.front().size(); ++i) {
    mot::SequenceCounts total;
    for (std::size_t d = 0; d < by_input.size(); ++d) {
      for (std::size_t s = 0; s < by_input[d][i].size(); ++s) {
        if (use[d][s]) total += by_input[d][i][s];
      }
    }
    by_interval.push_back(mot::summarize(total));
  }
  return by_interval;
}

// One cell's metrics: the candidate's counts for one input and interval, pooled over the
// sequences `use` marks.
mot::Metrics pooled_cell(const Counts& counts, std::size_t candidate, std::size_t input,
                         std::size_t interval, const Mask& use) {
  mot::SequenceCounts total;
  const auto& runs = counts[candidate][input][interval];
  for (std::size_t s = 0; s < runs.size(); ++s) {
    if (use[input][s]) total += runs[s];
  }
  return mot::summarize(total);
}

// How many (input, interval) cells of the runs `use` marks the candidate holds against every
// reference: MOTA and IDF1 each at least the reference's.
int cells_held(const Counts& counts, std::size_t candidate, std::size_t first_reference,
               const Mask& use) {
  int held = 0;
  for (std::size_t d = 0; d < use.size(); ++d) {
    if (std::none_of(use[d].begin(), use[d].end(), [](bool u) { return u; })) continue;
    for (std::size_t i = 0; i < counts[candidate][d].size(); ++i) {
      const mot::Metrics mine = pooled_cell(counts, candidate, d, i, use);
      bool holds = true;
      for (std::size_t r = first_reference; r < counts.size() && holds; ++r) {
        const mot::Metrics theirs = pooled_cell(counts, r, d, i, use);
        holds = mine.mota >= theirs.mota && mine.idf1 >= theirs.idf1;
      }
      held += holds ? 1 : 0;
    }
  }
  return held;
}

// The best of the first `candidates` entries of `counts` on the runs `use` marks (the rest are
// references): the most cells held against the references, then the best selection score; the
// first of equals.
std::size_t choose(const Counts& counts, std::size_t candidates, const Mask& use) {
  std::size_t best = 0;
  int best_held = -1;
  double best_score = -1e300;
  for (std::size_t c = 0; c < candidates; ++c) {
    const int held = candidates < counts.size() ? cells_held(counts, c, candidates, use) : 0;
    const double score = selection_score(pooled(counts, c, use));
    if (held > best_held || (held == best_held && score > best_score)) {
      best = c;
      best_held = held;
      best_score = score;
    }
  }
  return best;
}

StudyTable table_of(const std::string& name, StudyInput input, const std::vector<int>& intervals,
                    const std::vector<mot::Metrics>& by_interval,
                    const tracker::TrackerConfig& config) {
  StudyTable table{StudyConfiguration{name, "cv", config}, input, {}};
  for (std::size_t i = 0; i < intervals.size(); ++i)
    table.rows.push_back(StudyRow{intervals[i], by_interval[i]});
  return table;
}

}  // namespace

double selection_score(const std::vector<mot::Metrics>& by_interval) {
  if (by_interval.empty()) return 0.0;
  double sum = 0.0;
  for (const mot::Metrics& m : by_interval) sum += 0.5 * (m.mota + m.idf1);
  return sum / static_cast<double>(by_interval.size());
}

CrossValidation cross_validate(const std::vector<LoadedSequence>& dataset,
                               const std::vector<StudyConfiguration>& candidates,
                               const std::vector<StudyInput>& inputs,
                               const std::vector<int>& intervals, int jobs,
                               const std::atomic<bool>* stop,
                               const std::vector<StudyConfiguration>& references,
                               const RunProgress& progress) {
  if (dataset.size() < 2 || candidates.empty() || inputs.empty() || intervals.empty())
    throw std::invalid_argument(
        "cross-validation needs two sequences, a candidate, a detector "
        "and an interval");
  std::vector<StudyConfiguration> runs = candidates;
  runs.insert(runs.end(), references.begin(), references.end());
  const Counts counts = count_everything(dataset, runs, inputs, intervals, jobs, stop, progress);
  const std::size_t n_c = candidates.size();
  if (stop != nullptr && stop->load(std::memory_order_relaxed)) return {};
  const std::size_t n_s = dataset.size();
  const std::size_t n_d = inputs.size();

  CrossValidation cv;
  const Mask everything(n_d, std::vector<bool>(n_s, true));
  const std::size_t in_sample = choose(counts, n_c, everything);
  cv.in_sample_choice = candidates[in_sample].name;
  for (std::size_t c = 0; c < n_c; ++c)
    cv.in_sample_scores.push_back(CandidateScore{
        candidates[c].name, n_c < counts.size() ? cells_held(counts, c, n_c, everything) : 0,
        selection_score(pooled(counts, c, everything))});

  for (std::size_t d = 0; d < n_d; ++d) {
    std::vector<mot::SequenceCounts> held_out(intervals.size());
    for (std::size_t k = 0; k < n_s; ++k) {
      // Train on the other sequences through the other detectors (the same one if it is alone).
      Mask train(n_d, std::vector<bool>(n_s, true));
      for (std::size_t e = 0; e < n_d; ++e) {
        if (e == d && n_d > 1) train[e].assign(n_s, false);
        train[e][k] = false;
      }
      const std::size_t chosen = choose(counts, n_c, train);
      for (std::size_t i = 0; i < intervals.size(); ++i) held_out[i] += counts[chosen][d][i][k];
      cv.folds.push_back(FoldChoice{dataset[k].info.name, std::string(to_string(inputs[d])),
                                    candidates[chosen].name});
    }
    std::vector<mot::Metrics> held_out_metrics;
    for (const auto& total : held_out) held_out_metrics.push_back(mot::summarize(total));
    // The held-out table has no single configuration: it carries the in-sample choice's, which
    // is what the folds estimate.
    cv.tables.push_back(table_of("cv-held-out", inputs[d], intervals, held_out_metrics,
                                 candidates[in_sample].config));
    Mask this_input(n_d, std::vector<bool>(n_s, false));
    this_input[d].assign(n_s, true);
    cv.tables.push_back(table_of("cv-in-sample", inputs[d], intervals,
                                 pooled(counts, in_sample, this_input),
                                 candidates[in_sample].config));
  }
  return cv;
}

std::string format_folds_markdown(const CrossValidation& cv) {
  std::string out = fmt::format(
      "Chosen on every sequence and detector (in-sample): `{}`\n\n| held-out detector | held-out "
      "sequence | chosen on the rest | same as in-sample |\n|---|---|---|:---:|\n",
      cv.in_sample_choice);
  for (const auto& fold : cv.folds) {
    out += fmt::format("| {} | {} | `{}` | {} |\n", fold.detector, fold.held_out, fold.chosen,
                       fold.chosen == cv.in_sample_choice ? "yes" : "no");
  }
  out +=
      "\n| candidate | cells held on everything | selection score on everything |\n"
      "|---|---:|---:|\n";
  for (const auto& score : cv.in_sample_scores)
    out += fmt::format("| `{}` | {} | {:.2f} |\n", score.name, score.cells_held, score.mean);
  return out;
}

}  // namespace rtmot::study
