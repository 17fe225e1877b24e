#include "study/study_report.hpp"

#include <fmt/format.h>

#include <map>
#include <system_error>

#include "common/input_error.hpp"
#include "common/output_file.hpp"
#include "study/svg_line_plot.hpp"

namespace rtmot::study {
namespace {

namespace fs = std::filesystem;

constexpr const char* kColumns[] = {"interval", "Rcll", "Prcn", "FAR", "GT",  "MT",
                                    "PT",       "ML",   "FP",   "FN",  "IDs", "FM",
                                    "MOTA",     "MOTP", "IDF1", "HOTA"};

std::vector<std::string> cells(const StudyRow& row) {
  const mot::Metrics& m = row.metrics;
  return {std::to_string(row.interval),       fmt::format("{:.1f}", m.recall),
          fmt::format("{:.1f}", m.precision), fmt::format("{:.2f}", m.false_alarms_per_frame),
          std::to_string(m.gt_tracks),        std::to_string(m.mostly_tracked),
          std::to_string(m.partly_tracked),   std::to_string(m.mostly_lost),
          std::to_string(m.false_positives),  std::to_string(m.false_negatives),
          std::to_string(m.id_switches),      std::to_string(m.fragmentations),
          fmt::format("{:.1f}", m.mota),      fmt::format("{:.1f}", m.motp),
          fmt::format("{:.1f}", m.idf1),      fmt::format("{:.1f}", m.hota)};
}

std::string joined(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (const auto& part : parts) {
    if (!out.empty()) out += separator;
    out += part;
  }
  return out;
}

std::string short_title(StudyInput input) {
  if (input == StudyInput::detections) return "det/det.txt";
  if (input == StudyInput::ground_truth) return "gt/gt.txt";
  return std::string(to_string(input));
}

// What a plot's title says of its input.
std::string plot_subject(StudyInput input) {
  if (input == StudyInput::detections) return "detections";
  if (input == StudyInput::ground_truth) return "ground truth as detector";
  return std::string(to_string(input));
}

std::string table_title(const StudyTable& table) {
  return fmt::format("{} on {}", table.configuration.name, short_title(table.input));
}

struct PlottedMetric {
  const char* file_name;
  const char* label;
  double (*value)(const mot::Metrics&);
};

const PlottedMetric kPlottedMetrics[] = {
    {"mota", "MOTA (%)", [](const mot::Metrics& m) { return m.mota; }},
    {"idf1", "IDF1 (%)", [](const mot::Metrics& m) { return m.idf1; }},
    {"motp", "MOTP (%)", [](const mot::Metrics& m) { return m.motp; }},
    {"not-ml", "GT tracks not mostly lost (%)", &not_mostly_lost_percent},
};

}  // namespace

double not_mostly_lost_percent(const mot::Metrics& metrics) {
  if (metrics.gt_tracks == 0) return 0.0;
  return 100.0 *
         (1.0 - static_cast<double>(metrics.mostly_lost) / static_cast<double>(metrics.gt_tracks));
}

std::string format_study_csv(const StudyTable& table) {
  std::string out = joined({std::begin(kColumns), std::end(kColumns)}, ",") + "\n";
  for (const auto& row : table.rows) out += joined(cells(row), ",") + "\n";
  return out;
}

std::string format_study_markdown(const StudyTable& table) {
  std::string out = "| " + joined({std::begin(kColumns), std::end(kColumns)}, " | ") + " |\n|";
  for (std::size_t i = 0; i < std::size(kColumns); ++i) out += "---:|";
  out += "\n";
  for (const auto& row : table.rows) out += "| " + joined(cells(row), " | ") + " |\n";
  return out;
}

std::vector<fs::path> write_study(const fs::path& out_dir, const std::vector<StudyTable>& tables,
                                  const std::string& link_prefix) {
  std::vector<fs::path> written;
  const auto write = [&written](const fs::path& path, const std::string& text) {
    std::error_code error;
    fs::create_directories(path.parent_path(), error);
    if (error)
      throw InputError(path.parent_path().string(), 0, "", "cannot create: " + error.message());
    write_whole_file(path, text);
    written.push_back(path);
  };

  std::string summary;
  std::map<std::pair<std::string, std::string>, std::vector<const StudyTable*>> by_plot;
  std::map<std::string, StudyInput> input_named;
  for (const auto& table : tables) {
    const std::string input(to_string(table.input));
    input_named.emplace(input, table.input);
    const fs::path base = out_dir / "tables" / input / table.configuration.name;
    write(fs::path(base.string() + ".csv"), format_study_csv(table));
    write(fs::path(base.string() + ".md"), format_study_markdown(table));
    by_plot[{input, table.configuration.group}].push_back(&table);
  }

  std::string plots_section;
  for (const auto& [key, group_tables] : by_plot) {
    const auto& [input, group] = key;
    plots_section += fmt::format("\n### {} on {}\n\n", group, input_title(input_named.at(input)));
    for (const auto& metric : kPlottedMetrics) {
      LinePlot plot;
      plot.title = fmt::format("{} vs frame interval, {} ({})", metric.label, group,
                               plot_subject(input_named.at(input)));
      plot.x_label = "interval (process every N-th frame; log scale)";
      plot.y_label = metric.label;
      plot.log_x = true;
      for (const auto& row : group_tables.front()->rows) plot.x_ticks.push_back(row.interval);
      for (const StudyTable* table : group_tables) {
        LineSeries series{table->configuration.name, {}, table->configuration.group == "presets"};
        for (const auto& row : table->rows) {
          series.points.emplace_back(row.interval, metric.value(row.metrics));
        }
        plot.series.push_back(std::move(series));
      }
      if (group != "presets") {
        // Every plot also shows the presets, as the yardstick.
        for (const auto& table : tables) {
          if (table.configuration.group != "presets" ||
              std::string(to_string(table.input)) != input)
            continue;
          LineSeries series{table.configuration.name, {}, true};
          for (const auto& row : table.rows)
            series.points.emplace_back(row.interval, metric.value(row.metrics));
          plot.series.push_back(std::move(series));
        }
      }
      const std::string file = fmt::format("{}-{}-{}.svg", input, group, metric.file_name);
      write(out_dir / "plots" / file, render_svg(plot));
      plots_section += fmt::format("![{}]({}plots/{})\n", plot.title, link_prefix, file);
    }
  }

  summary += "## Plots\n" + plots_section + "\n## Tables\n";
  for (const auto& table : tables) {
    summary += fmt::format("\n### {}\n\n", table_title(table)) + format_study_markdown(table);
  }
  write(out_dir / "summary.md", summary);
  return written;
}

}  // namespace rtmot::study
