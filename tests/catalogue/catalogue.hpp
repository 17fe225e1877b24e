#pragma once
// The bad-input catalogue: every way a user can hand rtmot something wrong, what rtmot must answer
// (exit code, one error line naming file/line/field) and what it must leave behind. The table in
// catalogue_cases.cpp is the specification; docs/reliability.md lists it for humans.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/exit_codes.hpp"
#include "run_process.hpp"
#include "workspace.hpp"

namespace rtmot::test {

using Vars = std::map<std::string, std::string>;  // {name} placeholders in the arguments

struct CatalogueCase {
  std::string name;  // a GTest name: letters, digits, underscores
  std::string what;  // the bad input, in words (for the docs)
  std::function<void(Workspace&, Vars&)> setup;
  std::vector<std::string> args;  // after `rtmot`; {dir} is the workspace, {port} a busy port, ...
  ExitCode expected;
  std::vector<std::string> mentions;  // the error line names these (file, line, field); {vars} ok
  /// Optional: checks the outputs written before the error are complete and valid.
  std::function<void(const Workspace&)> check_outputs{};
  /// Optional: a file-size limit (a full disk), signals at chosen moments, a time limit.
  ProcessConditions conditions{};
  /// Optional (0: unchecked): the child's peak resident memory must stay below this.
  long max_rss_mb{0};
  /// Optional (empty: unchecked): the error line's exact text after "[error] ".
  std::string message{};
  /// Optional: shell commands run just before rtmot in the same process (`sh -c 'COMMANDS; exec
  /// rtmot ARGS'`), so that they can name rtmot's process id as $$ (a link planted at its
  /// temporary's name) or leave it a file descriptor (a lock another writer holds). {vars} ok.
  std::string shell_before{};
};

const std::vector<CatalogueCase>& catalogue();
/// Round two: what a hostile tester found (issue 11), a class per block; catalogue() includes it.
std::vector<CatalogueCase> hostile_cases();
/// Round three (issue 23), a class per block; catalogue() includes it.
std::vector<CatalogueCase> round_three_cases();
/// Round three (issue 23), the settings surface's classes: checked numbers and addresses.
std::vector<CatalogueCase> settings_cases();
/// Round three (issue 23, class 1): the detector's files through common/input_file.
std::vector<CatalogueCase> detector_file_cases();
/// Round four (issue 32): outputs' temporaries, FIFOs, locks and the log file; frames lists,
/// `count`'s lines file.
std::vector<CatalogueCase> round_four_files_cases();
/// Issue 22: command-line and configuration typos, one line each with the nearest valid name.
std::vector<CatalogueCase> usage_cases();
/// Round four (issue 32), the streams' classes: video on a full disk, H.265 at small sizes, the
/// listener's event counts, event names, --input-flip on a sequence, and the arguable ones.
std::vector<CatalogueCase> round_four_streams_cases();

}  // namespace rtmot::test
