#include "study/latency_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "common/frame_rate.hpp"
#include "common/output_file.hpp"
#include "common/simulated_clock.hpp"
#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "mot/sequence_counts.hpp"
#include "motio/track_runner.hpp"
#include "study/portable_random.hpp"
#include "study/svg_line_plot.hpp"
#include "tracker/presets.hpp"

namespace rtmot::study {
namespace {

namespace fs = std::filesystem;

// Per sequence: the jitter of sequence i draws from kJitterSeed + i.
constexpr std::uint64_t kJitterSeed = 401;

const motio::FrameDetections& detections_of(const LoadedSequence& sequence, StudyInput input) {
  if (input.kind == StudyInput::Kind::detections) return sequence.detections;
  if (input.kind == StudyInput::Kind::ground_truth) return sequence.gt_detections;
  return sequence.synthetic.at(static_cast<std::size_t>(input.synthetic));
}

// The rows of the processed frames only: what the output is without full-rate.
std::vector<motio::MotRow> rows_of_processed(const motio::TrackRun& run) {
  std::vector<motio::MotRow> rows;
  rows.reserve(run.tracks.size());
  for (const motio::MotRow& row : run.tracks) {
    if (std::binary_search(run.processed_frames.begin(), run.processed_frames.end(), row.frame))
      rows.push_back(row);
  }
  return rows;
}

// The latency for a sequence: latency_ms, or `frames` of its frame periods plus 1 us. The detector
// then becomes free just after the frame `frames` periods on arrived and takes it; exactly
// `frames` periods would meet that frame's pts to the nanosecond, and the pts' rounding would
// decide (1 us of drift per frame taken stays below a period for 33000 frames at 30 fps).
DetectorLatency for_sequence(DetectorLatency latency, const motio::SequenceInfo& info) {
  constexpr double kPastTheFrameMs = 1e-3;
  if (latency.frames > 0.0)
    latency.latency_ms = latency.frames * 1000.0 / info.frame_rate + kPastTheFrameMs;
  return latency;
}

// One preset on one input at one latency, every sequence pooled.
LatencyRow run_one(const std::vector<LoadedSequence>& dataset, const tracker::TrackerConfig& config,
                   StudyInput input, const DetectorLatency& latency) {
  LatencyRow row{latency, 0, 0, {}, {}, {}, {}, 0};
  mot::SequenceCounts processed;
  mot::SequenceCounts full_rate;
  mot::SequenceCounts full_rate_output;
  mot::SequenceCounts full_rate_output_every;
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const LoadedSequence& sequence = dataset[i];
    motio::TrackOptions options;
    options.config = config;
    options.frames = pipeline_frames(sequence.info, latency, kJitterSeed + i);
    // One run gives both outputs: the predictions do not change the tracker, so the rows of the
    // processed frames are the same as without them.
    options.predict_skipped = true;
    const motio::TrackRun run =
        motio::track_detections(detections_of(sequence, input), sequence.info, options);
    const std::vector<motio::MotRow> processed_rows = rows_of_processed(run);
    mot::PrepareOptions prepare;
    prepare.sequence_length = sequence.info.length;
    prepare.gt_file = sequence.info.name + "/gt/gt.txt";
    prepare.results_file = sequence.info.name + " (tracked in memory)";
    full_rate += mot::count_all(mot::prepare_sequence(sequence.gt_rows, processed_rows, prepare));
    full_rate_output +=
        mot::count_all(mot::prepare_sequence(sequence.gt_rows, run.tracks, prepare));
    options.predict_min_hits = 0;
    const motio::TrackRun every =
        motio::track_detections(detections_of(sequence, input), sequence.info, options);
    full_rate_output_every +=
        mot::count_all(mot::prepare_sequence(sequence.gt_rows, every.tracks, prepare));
    prepare.frames = run.processed_frames;
    processed += mot::count_all(mot::prepare_sequence(sequence.gt_rows, processed_rows, prepare));
    row.frames_predicted += run.frames_predicted;
    row.frames_processed += run.frames_processed;
    row.frames += sequence.info.length;
  }
  row.processed = mot::summarize(processed);
  row.full_rate = mot::summarize(full_rate);
  row.full_rate_output = mot::summarize(full_rate_output);
  row.full_rate_output_every = mot::summarize(full_rate_output_every);
  return row;
}

std::string input_name(StudyInput input) {
  return std::string(to_string(input));
}

std::string file_stem(const LatencyTable& table) {
  return input_name(table.input) + "-" + table.preset;
}

constexpr const char* kColumns[] = {"latency",
                                    "frames processed",
                                    "MOTA processed",
                                    "IDF1 processed",
                                    "IDs processed",
                                    "MOTA full rate",
                                    "IDF1 full rate",
                                    "FN full rate",
                                    "MOTA full-rate output",
                                    "IDF1 full-rate output",
                                    "FN full-rate output",
                                    "FP full-rate output"};

std::vector<std::string> cells(const LatencyRow& row) {
  const double share = row.frames > 0 ? 100.0 * static_cast<double>(row.frames_processed) /
                                            static_cast<double>(row.frames)
                                      : 0.0;
  return {latency_label(row.latency),
          fmt::format("{:.1f} %", share),
          fmt::format("{:.1f}", row.processed.mota),
          fmt::format("{:.1f}", row.processed.idf1),
          std::to_string(row.processed.id_switches),
          fmt::format("{:.1f}", row.full_rate.mota),
          fmt::format("{:.1f}", row.full_rate.idf1),
          std::to_string(row.full_rate.false_negatives),
          fmt::format("{:.1f}", row.full_rate_output.mota),
          fmt::format("{:.1f}", row.full_rate_output.idf1),
          std::to_string(row.full_rate_output.false_negatives),
          std::to_string(row.full_rate_output.false_positives)};
}

struct PlottedMetric {
  const char* file_name;
  const char* label;
  mot::Metrics LatencyRow::*scored;
  double (*value)(const mot::Metrics&);
};

const PlottedMetric kPlotted[] = {
    {"mota-processed", "MOTA on the processed frames (%)", &LatencyRow::processed,
     [](const mot::Metrics& m) { return m.mota; }},
    {"idf1-processed", "IDF1 on the processed frames (%)", &LatencyRow::processed,
     [](const mot::Metrics& m) { return m.idf1; }},
    {"mota-full", "MOTA at the full frame rate (%)", &LatencyRow::full_rate,
     [](const mot::Metrics& m) { return m.mota; }},
    {"idf1-full", "IDF1 at the full frame rate (%)", &LatencyRow::full_rate,
     [](const mot::Metrics& m) { return m.idf1; }},
    {"mota-full-output", "MOTA of the full-rate output (%)", &LatencyRow::full_rate_output,
     [](const mot::Metrics& m) { return m.mota; }},
    {"idf1-full-output", "IDF1 of the full-rate output (%)", &LatencyRow::full_rate_output,
     [](const mot::Metrics& m) { return m.idf1; }},
};

}  // namespace

std::string latency_label(const DetectorLatency& latency) {
  if (latency.frames > 0.0) return fmt::format("{:g} frames", latency.frames);
  if (latency.latency_ms <= 0.0) return "0 ms (every frame)";
  std::string label = fmt::format("{:g} ms", latency.latency_ms);
  if (latency.jitter > 0.0) label += fmt::format(" ±{:g}%", 100.0 * latency.jitter);
  return label;
}

std::vector<DetectorLatency> default_latencies() {
  const double fixed[] = {33.0, 66.0, 125.0, 250.0, 500.0, 1000.0};
  std::vector<DetectorLatency> latencies{{0.0, 0.0}};
  for (const double ms : fixed) latencies.push_back({ms, 0.0});
  for (const double ms : fixed) latencies.push_back({ms, 0.5});
  // Every 5th and every 10th frame of each sequence, whatever its rate (the full-rate output's
  // goal in issue 21).
  latencies.push_back({0.0, 0.0, 5.0});
  latencies.push_back({0.0, 0.0, 10.0});
  return latencies;
}

std::vector<int> pipeline_frames(const motio::SequenceInfo& info, const DetectorLatency& asked,
                                 std::uint64_t seed) {
  const DetectorLatency latency = for_sequence(asked, info);
  SimulatedClock clock(simulated_latency_ns(latency.latency_ms));
  Random random(seed);
  std::vector<int> frames;
  for (int frame = 1; frame <= info.length; ++frame) {
    if (latency.jitter > 0.0) {
      // One draw per frame whether taken or not: the draws do not depend on the decisions.
      const double factor = 1.0 + latency.jitter * (2.0 * random.uniform() - 1.0);
      clock.set_latency_ns(simulated_latency_ns(latency.latency_ms * factor));
    }
    const std::int64_t pts = frame_time_ns(frame - 1, info.frame_rate);
    const auto next =
        frame < info.length ? std::optional(frame_time_ns(frame, info.frame_rate)) : std::nullopt;
    if (clock.takes(pts, next)) frames.push_back(frame);
  }
  return frames;
}

std::vector<LatencyTable> run_latency_sweep(const std::vector<LoadedSequence>& dataset,
                                            const std::vector<std::string>& presets,
                                            const std::vector<StudyInput>& inputs,
                                            const std::vector<DetectorLatency>& latencies, int jobs,
                                            const std::atomic<bool>* stop) {
  std::vector<LatencyTable> tables;
  std::vector<tracker::TrackerConfig> configs;
  for (const std::string& preset : presets) {
    for (const StudyInput input : inputs) {
      tables.push_back({preset, input, std::vector<LatencyRow>(latencies.size())});
      configs.push_back(*tracker::find_preset(preset));
    }
  }
  const std::size_t per_table = latencies.size();
  const std::size_t total = tables.size() * per_table;
  // Each run writes only its own preallocated row: the workers share the next run's index.
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    for (std::size_t run = next++; run < total; run = next++) {
      if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;
      LatencyTable& table = tables[run / per_table];
      try {
        table.rows[run % per_table] =
            run_one(dataset, configs[run / per_table], table.input, latencies[run % per_table]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = total;
      }
    }
  };
  std::vector<std::thread> workers;
  const int threads = std::clamp(jobs, 1, static_cast<int>(std::max<std::size_t>(total, 1)));
  for (int t = 1; t < threads; ++t) workers.emplace_back(work);
  work();
  for (auto& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  return tables;
}

std::string format_latency_markdown(const LatencyTable& table) {
  std::string out = "|";
  std::string rule = "|";
  for (const char* column : kColumns) {
    out += fmt::format(" {} |", column);
    rule += column == kColumns[0] ? "---|" : "---:|";
  }
  out += "\n" + rule + "\n";
  for (const LatencyRow& row : table.rows) {
    out += "|";
    for (const std::string& cell : cells(row)) out += " " + cell + " |";
    out += "\n";
  }
  return out;
}

std::string format_latency_csv(const LatencyTable& table) {
  std::string out =
      "latency_ms,jitter,latency_frames,frames_processed,frames,mota_processed,idf1_processed,"
      "ids_processed,mota_full_rate,idf1_full_rate,fn_full_rate,mota_full_output,"
      "idf1_full_output,fn_full_output,fp_full_output,ids_full_output,mota_full_output_every,"
      "idf1_full_output_every,fp_full_output_every\n";
  for (const LatencyRow& row : table.rows) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       row.latency.latency_ms, row.latency.jitter, row.latency.frames,
                       row.frames_processed, row.frames, row.processed.mota, row.processed.idf1,
                       row.processed.id_switches, row.full_rate.mota, row.full_rate.idf1,
                       row.full_rate.false_negatives, row.full_rate_output.mota,
                       row.full_rate_output.idf1, row.full_rate_output.false_negatives,
                       row.full_rate_output.false_positives, row.full_rate_output.id_switches,
                       row.full_rate_output_every.mota, row.full_rate_output_every.idf1,
                       row.full_rate_output_every.false_positives);
  }
  return out;
}

std::vector<fs::path> write_latency_sweep(const fs::path& out_dir,
                                          const std::vector<LatencyTable>& tables) {
  const fs::path dir = out_dir / "latency";
  std::vector<fs::path> written;
  const auto write = [&](const fs::path& path, const std::string& text) {
    write_whole_file(path, text);
    written.push_back(path);
  };
  std::error_code error;
  fs::create_directories(dir, error);  // write_whole_file names the folder if this failed
  std::string summary =
      "# Latency sweep: the pipeline's own frame skipping behind a slow detector\n\n"
      "Scored on the frames the pipeline processed, at the full frame rate (every skipped "
      "frame's boxes missed), and the full-rate output at the full frame rate (every skipped "
      "frame given the tracks' predicted boxes, docs/full-rate.md). All sequences pooled.\n";
  std::vector<StudyInput> inputs;
  for (const LatencyTable& table : tables) {
    write(dir / (file_stem(table) + ".md"), format_latency_markdown(table));
    write(dir / (file_stem(table) + ".csv"), format_latency_csv(table));
    if (std::find(inputs.begin(), inputs.end(), table.input) == inputs.end())
      inputs.push_back(table.input);
  }
  for (const StudyInput input : inputs) {
    summary += fmt::format("\n## {}\n\n", input_title(input));
    for (const PlottedMetric& metric : kPlotted) {
      LinePlot plot;
      plot.title = fmt::format("{} vs detector latency ({})", metric.label, input_name(input));
      plot.x_label = "simulated detector latency (ms)";
      plot.y_label = metric.label;
      plot.log_x = true;
      for (const LatencyTable& table : tables) {
        if (table.input != input) continue;
        for (const bool jittered : {false, true}) {
          LineSeries series{table.preset + (jittered ? " ±jitter" : ""), {}, !jittered};
          for (const LatencyRow& row : table.rows) {
            // Latencies in frame periods differ per sequence: tables only.
            if (row.latency.latency_ms <= 0.0 || row.latency.frames > 0.0 ||
                (row.latency.jitter > 0.0) != jittered)
              continue;
            const mot::Metrics& m = row.*metric.scored;
            series.points.emplace_back(row.latency.latency_ms, metric.value(m));
            if (!jittered && table.preset == tables.front().preset)
              plot.x_ticks.push_back(row.latency.latency_ms);
          }
          if (!series.points.empty()) plot.series.push_back(std::move(series));
        }
      }
      const std::string file = fmt::format("{}-{}.svg", input_name(input), metric.file_name);
      write(dir / file, render_svg(plot));
      summary += fmt::format("![{}]({})\n", plot.title, file);
    }
    for (const LatencyTable& table : tables) {
      if (table.input != input) continue;
      summary += fmt::format("\n### {} on {}\n\n", table.preset, input_name(input)) +
                 format_latency_markdown(table);
    }
  }
  write(dir / "summary.md", summary);
  return written;
}

}  // namespace rtmot::study
