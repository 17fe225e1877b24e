#pragma once
// Runs a program as a child process, capturing stdout and stderr, with a time limit: the catalogue
// must see exactly what a user or a script sees (exit code, signal, the printed lines).
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
  std::string out;
  std::string err;
};

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                          std::chrono::seconds time_limit);

}  // namespace rtmot::test
