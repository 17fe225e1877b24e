#pragma once
// How `rtmot` is put together: each subcommand lives in its own cmd_*.cpp, registers its options on
// the top-level CLI and hands back what to run if the user chose it.
#include <CLI/CLI.hpp>
#include <functional>

namespace rtmot::app {

struct Subcommand {
  CLI::App* cli{nullptr};
  std::function<int()> run;  // returns the process exit code (common/exit_codes.hpp)
  /// True when `run` takes SIGINT/SIGTERM itself (platform::StopSignals) to stop cleanly: main()
  /// keeps them blocked from its first instruction, so one sent while the program starts waits
  /// for it instead of killing the process. False: main() unblocks them (default action).
  bool stops_on_signals{false};
};

// One line per subcommand (keep alphabetical). Defined in apps/cmd_<name>.cpp.
// SUBCOMMAND-DECLARATIONS
Subcommand add_count_command(CLI::App& parent);
Subcommand add_eval_command(CLI::App& parent);
Subcommand add_listen_command(CLI::App& parent);
Subcommand add_model_command(CLI::App& parent);
Subcommand add_run_command(CLI::App& parent);
Subcommand add_soak_command(CLI::App& parent);
Subcommand add_study_command(CLI::App& parent);
Subcommand add_track_command(CLI::App& parent);
}  // namespace rtmot::app
