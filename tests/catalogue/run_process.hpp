#pragma once
// Runs a program as a child process, capturing stdout and stderr, with a time limit: the catalogue
// must see exactly what a user or a script sees (exit code, signal, the printed lines), and can
// put the child under the conditions a hostile tester would: a file-size limit (a full disk: the
// write that crosses it fails, as with ENOSPC), and signals at chosen moments.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace rtmot::test {

struct ProcessResult {
  bool exited{false};  // false: killed by a signal (a crash) or by the time limit
  int exit_code{-1};
  int signal{0};
  bool timed_out{false};
  long max_rss_kb{0};  // the child's peak resident memory
  std::string out;
  std::string err;
};

/// A signal sent `delay` after the child printed `after_output` (on stdout or stderr), or after the
/// previous signal when that is empty. Timing by output, not by the clock: a loaded machine
/// spends a varying time loading the program's ~250 shared libraries.
struct TimedSignal {
  int signal{0};
  std::chrono::milliseconds delay{0};
  std::string after_output;
  /// If `after_output` has not appeared this long after the start, send anyway (0: never). Only
  /// an older build that does not print it needs this.
  std::chrono::milliseconds fallback{0};
  /// And only once this file exists and is not empty (empty path: no condition): a stop that must
  /// find output already written waits for it, however slowly a loaded machine starts the run.
  std::filesystem::path after_file{};
};

struct ProcessConditions {
  std::chrono::seconds time_limit{60};
  /// RLIMIT_FSIZE in bytes (0: none). SIGXFSZ keeps its default action (rtmot ignores it itself,
  /// so a write beyond it fails with EFBIG).
  std::uint64_t file_size_limit{0};
  /// RLIMIT_AS in bytes (0: none): a case whose old failure was eating memory stays bounded.
  std::uint64_t address_space_limit{0};
  /// Where stdout goes instead of a file the test reads (e.g. /dev/full: a full disk).
  std::string stdout_device{};
  /// Signals to send in turn (e.g. SIGTERM, then SIGTERM or SIGKILL).
  std::vector<TimedSignal> signals;
};

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                          std::chrono::seconds time_limit);
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                          const ProcessConditions& conditions);

/// The rtmot binary under test: RTMOT_BINARY, or $RTMOT_CATALOGUE_BINARY when set (to run the
/// catalogue against an older build and see which cases fail there).
std::string rtmot_binary();

}  // namespace rtmot::test
