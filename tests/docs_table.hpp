#pragma once
// A table of a hand-written doc that the code generates: between its begin and end markers the doc
// must show the table as the code makes it, so that it cannot drift. Run with RTMOT_UPDATE_DOCS
// set, the test rewrites the table instead of failing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rtmot::test {

/// `text` as one markdown table cell: a '|' would end the cell.
inline std::string markdown_cell(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) {
    text.replace(at, 1, "\\|");
  }
  return text;
}

struct DocsText {
  std::string text;          // the whole doc, as it is after the check
  std::size_t table_end{0};  // where the end marker starts in `text`
  bool found{false};         // both markers are there
};

/// Checks (or, with RTMOT_UPDATE_DOCS set, rewrites) the table between `begin` and `end` in the
/// doc at `path`; a test failure names the doc and how to update it.
inline DocsText check_generated_table(const std::filesystem::path& path, const std::string& begin,
                                      const std::string& end, const std::string& table) {
  DocsText docs;
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  docs.text = buffer.str();
  const std::size_t begin_at = docs.text.find(begin);
  docs.table_end = docs.text.find(end);
  if (begin_at == std::string::npos || docs.table_end == std::string::npos) {
    ADD_FAILURE() << path << " has no table between\n" << begin << "and\n" << end;
    return docs;
  }
  docs.found = true;
  const std::size_t body = begin_at + begin.size();
  const std::string shown = docs.text.substr(body, docs.table_end - body);
  if (shown != table && std::getenv("RTMOT_UPDATE_DOCS") != nullptr) {
    docs.text.replace(body, docs.table_end - body, table);
    docs.table_end = body + table.size();
    std::ofstream out(path);
    out << docs.text;
    out.close();
    EXPECT_TRUE(out) << "cannot rewrite " << path;
    return docs;
  }
  EXPECT_EQ(shown, table) << path << ": the table after\n"
                          << begin << "is out of date: run this test with RTMOT_UPDATE_DOCS=1";
  return docs;
}

}  // namespace rtmot::test
