#include "mot/metrics_report.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/input_error.hpp"

namespace rtmot::mot {

namespace {

struct Column {
  const char* name;
  int decimals;  // -1: an integer count
  std::function<double(const Metrics&)> value;
};

const std::vector<Column>& columns() {
  static const std::vector<Column> table = {
      {"IDF1", 1, [](const Metrics& m) { return m.idf1; }},
      {"IDP", 1, [](const Metrics& m) { return m.idp; }},
      {"IDR", 1, [](const Metrics& m) { return m.idr; }},
      {"Rcll", 1, [](const Metrics& m) { return m.recall; }},
      {"Prcn", 1, [](const Metrics& m) { return m.precision; }},
      {"FAR", 2, [](const Metrics& m) { return m.false_alarms_per_frame; }},
      {"GT", -1, [](const Metrics& m) { return static_cast<double>(m.gt_tracks); }},
      {"MT", -1, [](const Metrics& m) { return static_cast<double>(m.mostly_tracked); }},
      {"PT", -1, [](const Metrics& m) { return static_cast<double>(m.partly_tracked); }},
      {"ML", -1, [](const Metrics& m) { return static_cast<double>(m.mostly_lost); }},
      {"FP", -1, [](const Metrics& m) { return static_cast<double>(m.false_positives); }},
      {"FN", -1, [](const Metrics& m) { return static_cast<double>(m.false_negatives); }},
      {"IDs", -1, [](const Metrics& m) { return static_cast<double>(m.id_switches); }},
      {"FM", -1, [](const Metrics& m) { return static_cast<double>(m.fragmentations); }},
      {"MOTA", 1, [](const Metrics& m) { return m.mota; }},
      {"MOTP", 1, [](const Metrics& m) { return m.motp; }},
      {"MOTAL", 1, [](const Metrics& m) { return m.motal; }},
      {"HOTA", 1, [](const Metrics& m) { return m.hota; }},
      {"DetA", 1, [](const Metrics& m) { return m.deta; }},
      {"AssA", 1, [](const Metrics& m) { return m.assa; }},
      {"LocA", 1, [](const Metrics& m) { return m.loca; }},
  };
  return table;
}

std::string cell(const Column& column, const Metrics& metrics) {
  char buffer[64];
  const double value = column.value(metrics);
  if (column.decimals < 0) {
    std::snprintf(buffer, sizeof buffer, "%lld", static_cast<long long>(value));
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*f", column.decimals, value);
  }
  return buffer;
}

std::vector<const SequenceScore*> lines(const EvaluationReport& report) {
  std::vector<const SequenceScore*> all;
  for (const auto& sequence : report.sequences) all.push_back(&sequence);
  all.push_back(&report.overall);
  return all;
}

}  // namespace

std::string format_table(const EvaluationReport& report) {
  const auto all = lines(report);
  std::size_t name_width = 8;
  for (const auto* line : all) name_width = std::max(name_width, line->name.size());
  std::vector<std::size_t> widths;
  for (const auto& column : columns()) {
    std::size_t width = std::strlen(column.name);
    for (const auto* line : all) width = std::max(width, cell(column, line->metrics).size());
    widths.push_back(width);
  }
  const auto pad_left = [](const std::string& text, std::size_t width) {
    return std::string(width > text.size() ? width - text.size() : 0, ' ') + text;
  };
  std::string out = "Sequence" + std::string(name_width - 8, ' ');
  for (std::size_t c = 0; c < columns().size(); ++c)
    out += " " + pad_left(columns()[c].name, widths[c]);
  out += "\n";
  for (const auto* line : all) {
    out += line->name + std::string(name_width - line->name.size(), ' ');
    for (std::size_t c = 0; c < columns().size(); ++c) {
      out += " " + pad_left(cell(columns()[c], line->metrics), widths[c]);
    }
    out += "\n";
  }
  return out;
}

std::string format_csv(const EvaluationReport& report) {
  std::string out = "sequence";
  for (const auto& column : columns()) out += std::string(",") + column.name;
  out += "\n";
  for (const auto* line : lines(report)) {
    out += line->name;
    for (const auto& column : columns()) out += "," + cell(column, line->metrics);
    out += "\n";
  }
  return out;
}

std::string format_json(const EvaluationReport& report) {
  nlohmann::json sequences = nlohmann::json::array();
  for (const auto* line : lines(report)) {
    nlohmann::json entry;
    entry["sequence"] = line->name;
    for (const auto& column : columns()) {
      const double value = column.value(line->metrics);
      if (column.decimals < 0) {
        entry[column.name] = static_cast<long long>(value);
      } else {
        entry[column.name] = value;
      }
    }
    const ClearCounts& c = line->counts.clear;
    entry["counts"] = {{"gt_detections", c.gt_detections},
                       {"true_positives", c.true_positives},
                       {"frames", c.frames},
                       {"idtp", line->counts.identity.true_positives},
                       {"idfp", line->counts.identity.false_positives},
                       {"idfn", line->counts.identity.false_negatives}};
    sequences.push_back(entry);
  }
  return sequences.dump(2) + "\n";
}

}  // namespace rtmot::mot
