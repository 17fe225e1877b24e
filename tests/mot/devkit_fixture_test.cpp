// The scorer against the official MOTChallenge devkit: every column of expected-devkit.csv, to the
// precision the devkit prints, from the fixture's gt and a published tracker's result.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "mot/evaluation.hpp"
#include "shared_data.hpp"

namespace rtmot::mot {
namespace {

using Row = std::map<std::string, std::string>;

std::vector<Row> read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream header_stream(line);
  for (std::string cell; std::getline(header_stream, cell, ',');) header.push_back(cell);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream stream(line);
    Row row;
    std::size_t column = 0;
    for (std::string cell; std::getline(stream, cell, ',') && column < header.size(); ++column) {
      row[header[column]] = cell;
    }
    rows.push_back(row);
  }
  return rows;
}

int decimals(const std::string& text) {
  const auto point = text.find('.');
  return point == std::string::npos ? 0 : static_cast<int>(text.size() - point - 1);
}

std::map<std::string, double> columns(const Metrics& m) {
  return {{"IDF1", m.idf1},
          {"IDP", m.idp},
          {"IDR", m.idr},
          {"Rcll", m.recall},
          {"Prcn", m.precision},
          {"FAR", m.false_alarms_per_frame},
          {"GT", static_cast<double>(m.gt_tracks)},
          {"MT", static_cast<double>(m.mostly_tracked)},
          {"PT", static_cast<double>(m.partly_tracked)},
          {"ML", static_cast<double>(m.mostly_lost)},
          {"FP", static_cast<double>(m.false_positives)},
          {"FN", static_cast<double>(m.false_negatives)},
          {"IDs", static_cast<double>(m.id_switches)},
          {"FM", static_cast<double>(m.fragmentations)},
          {"MOTA", m.mota},
          {"MOTP", m.motp},
          {"MOTAL", m.motal}};
}

TEST(DevkitFixture, EveryColumnOfEverySequenceMatchesTheDevkit) {
  const auto csv = test::shared_path("data/metrics-fixtures/expected-devkit.csv");
  RTMOT_REQUIRE_FILE(csv);
  const auto expected_rows = read_csv(csv);
  ASSERT_FALSE(expected_rows.empty());
  for (const Row& expected : expected_rows) {
    const std::string sequence = expected.at("sequence");
    SCOPED_TRACE(sequence);
    const auto dir = test::shared_path("data/metrics-fixtures/" + sequence);
    RTMOT_REQUIRE_FILE(dir / "result-CEM.txt");
    const SequenceScore score = evaluate_sequence(dir, dir / "result-CEM.txt");
    const auto actual = columns(score.metrics);
    for (const auto& [name, text] : expected) {
      if (name == "sequence") continue;
      ASSERT_TRUE(actual.count(name)) << "unknown column " << name;
      const double scale = std::pow(10.0, decimals(text));
      const double rounded = std::round(actual.at(name) * scale) / scale;
      EXPECT_NEAR(rounded, std::stod(text), 0.5 / scale)
          << name << ": expected " << text << ", computed " << actual.at(name);
    }
  }
}

}  // namespace
}  // namespace rtmot::mot
