// Runs the real `rtmot` binary on every case of the catalogue and checks what a user would see.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "catalogue.hpp"
#include "run_process.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

std::string fill(std::string text, const Vars& vars) {
  for (const auto& [name, value] : vars) {
    const std::string key = "{" + name + "}";
    for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  }
  return text;
}

// The lines of stderr that report the failure: log lines below error level are context, not the
// error. (CLI11's own two-line errors are gone: apps/cli_error.hpp writes one line.)
std::vector<std::string> error_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const bool context =
        line.find("[info]") != std::string::npos || line.find("[debug]") != std::string::npos ||
        line.find("[trace]") != std::string::npos || line.find("[warning]") != std::string::npos;
    if (!context) lines.push_back(line);
  }
  return lines;
}

}  // namespace

// Names the case instead of dumping its bytes in failure messages.
void PrintTo(const CatalogueCase& c, std::ostream* out) {
  *out << c.name;
}

namespace {

class Catalogue : public ::testing::TestWithParam<CatalogueCase> {};

TEST_P(Catalogue, FailsCleanlyWithTheDocumentedExitCode) {
  const CatalogueCase& c = GetParam();
  Workspace ws(c.name);
  Vars vars{{"dir", ws.dir().string()}, {"shared", shared_path("").string()}};
  c.setup(ws, vars);

  std::vector<std::string> argv{rtmot_binary()};
  if (!c.shell_before.empty()) {
    argv = {"/bin/sh", "-c", fill(c.shell_before, vars) + "; exec \"$0\" \"$@\"", rtmot_binary()};
  }
  for (const auto& arg : c.args) argv.push_back(fill(arg, vars));
  const ProcessResult run = run_process(argv, ws.dir(), c.conditions);

  std::string command;
  for (const auto& arg : argv) command += arg + " ";
  SCOPED_TRACE("case: " + c.what + "\ncommand: " + command + "\nstdout: " + run.out +
               "\nstderr: " + run.err);
  ASSERT_FALSE(run.timed_out) << "did not end within " << c.conditions.time_limit.count() << " s";
  ASSERT_TRUE(run.exited) << "killed by signal " << run.signal << " (a crash)";
  EXPECT_EQ(run.exit_code, to_int(c.expected));
#ifndef RTMOT_SANITIZED  // sanitizers' shadow memory and quarantine: see CMakeLists.txt
  if (c.max_rss_mb > 0) {
    EXPECT_LT(run.max_rss_kb / 1024, c.max_rss_mb)
        << "peak memory " << run.max_rss_kb / 1024 << " MB";
  }
#endif
  if (c.expected == ExitCode::ok) {  // a success (e.g. a clean stop): no error line at all
    EXPECT_TRUE(error_lines(run.err).empty()) << "error lines on a success";
    if (c.check_outputs) c.check_outputs(ws);
    return;
  }

  auto lines = error_lines(run.err);
  if (lines.empty()) {
    // Still check the rest, so that one wrong stream does not hide the other findings.
    for (const auto& line : error_lines(run.out)) {
      if (line.find("[error]") != std::string::npos || line.find("[critical]") != std::string::npos)
        lines.push_back(line);
    }
    if (!lines.empty()) ADD_FAILURE() << "the error line went to stdout, not stderr";
  }
  ASSERT_EQ(lines.size(), 1U) << "expected one error line on stderr";
  EXPECT_LE(lines[0].size(), 600U) << "one line, but a page long";
  for (const auto& mention : c.mentions) {
    EXPECT_NE(lines[0].find(fill(mention, vars)), std::string::npos)
        << "the error line does not name '" << fill(mention, vars) << "'";
  }
  if (!c.message.empty()) {
    const std::string level = "[error] ";
    const auto at = lines[0].find(level);
    ASSERT_NE(at, std::string::npos) << "not in the error format: " << lines[0];
    EXPECT_EQ(lines[0].substr(at + level.size()), fill(c.message, vars));
  }
  if (c.check_outputs) c.check_outputs(ws);
}

INSTANTIATE_TEST_SUITE_P(BadInputs, Catalogue, ::testing::ValuesIn(catalogue()),
                         [](const auto& info) { return info.param.name; });

TEST(CatalogueTable, HasAtLeast25CasesWithUniqueNames) {
  std::vector<std::string> names;
  for (const auto& c : catalogue()) names.push_back(c.name);
  EXPECT_GE(names.size(), 25U);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
}

}  // namespace
}  // namespace rtmot::test
