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

// One preset on one input at one latency, every sequence pooled.
LatencyRow run_one(const std::vector<LoadedSequence>& dataset, const tracker::TrackerConfig& config,
                   StudyInput input, const DetectorLatency& latency) {
  LatencyRow row{latency, 0, 0, {}, {}};
  mot::SequenceCounts processed;
  mot::SequenceCounts full_rate;
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const LoadedSequence& sequence = dataset[i];
    motio::TrackOptions options;
    options.config = config;
    options.frames = pipeline_frames(sequence.info, latency, kJitterSeed + i);
    const motio::TrackRun run =
        motio::track_detections(detections_of(sequence, input), sequence.info, options);
    mot::PrepareOptions prepare;
    prepare.sequence_length = sequence.info.length;
    prepare.gt_file = sequence.info.name + "/gt/gt.txt";
    prepare.results_file = sequence.info.name + " (tracked in memory)";
    full_rate += mot::count_all(mot::prepare_sequence(sequence.gt_rows, run.tracks, prepare));
    prepare.frames = run.processed_frames;
    processed += mot::count_all(mot::prepare_sequence(sequence.gt_rows, run.tracks, prepare));
    row.frames_processed += run.frames_processed;
    row.frames += sequence.info.length;
  }
  row.processed = mot::summarize(processed);
  row.full_rate = mot::summarize(full_rate);
  return row;
}

std::string input_name(StudyInput input) {
  return std::string(to_string(input));
}

std::string file_stem(const LatencyTable& table) {
  return input_name(table.input) + "-" + table.preset;
}

constexpr const char* kColumns[] = {"latency",        "frames processed", "MOTA processed",
                                    "IDF1 processed", "IDs processed",    "MOTA full rate",
                                    "IDF1 full rate", "FN full rate"};

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
          std::to_string(row.full_rate.false_negatives)};
}

struct PlottedMetric {
  const char* file_name;
  const char* label;
  bool full_rate;
  double (*value)(const mot::Metrics&);
};

const PlottedMetric kPlotted[] = {
    {"mota-processed", "MOTA on the processed frames (%)", false,
     [](const mot::Metrics& m) { return m.mota; }},
    {"idf1-processed", "IDF1 on the processed frames (%)", false,
     [](const mot::Metrics& m) { return m.idf1; }},
    {"mota-full", "MOTA at the full frame rate (%)", true,
     [](const mot::Metrics& m) { return m.mota; }},
    {"idf1-full", "IDF1 at the full frame rate (%)", true,
     [](const mot::Metrics& m) { return m.idf1; }},
};

}  // namespace

std::string latency_label(const DetectorLatency& latency) {
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
  return latencies;
}

std::vector<int> pipeline_frames(const motio::SequenceInfo& info, const DetectorLatency& latency,
                                 std::uint64_t seed) {
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
      "latency_ms,jitter,frames_processed,frames,mota_processed,idf1_processed,ids_processed,"
      "mota_full_rate,idf1_full_rate,fn_full_rate\n";
  for (const LatencyRow& row : table.rows) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", row.latency.latency_ms,
                       row.latency.jitter, row.frames_processed, row.frames, row.processed.mota,
                       row.processed.idf1, row.processed.id_switches, row.full_rate.mota,
                       row.full_rate.idf1, row.full_rate.false_negatives);
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
      "Scored on the frames the pipeline processed, and at the full frame rate (every skipped "
      "frame's boxes missed). All sequences pooled.\n";
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
            if (row.latency.latency_ms <= 0.0 || (row.latency.jitter > 0.0) != jittered) continue;
            const mot::Metrics& m = metric.full_rate ? row.full_rate : row.processed;
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
