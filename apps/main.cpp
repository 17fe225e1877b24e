// rtmot: one executable, one subcommand per job (`rtmot --help` lists them).
#include <pthread.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <opencv2/core/utils/logger.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "apps/cli_error.hpp"
#include "apps/name_check.hpp"
#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "platform/log_setup.hpp"

namespace {

// What a command printed must have reached stdout: a results table lost to a full disk or a
// closed pipe is a failure, as for coreutils (close_stdout). Returns the error line, or "".
std::string stdout_failure() {
  errno = 0;
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (!failed) return {};
  return std::string("cannot write to stdout: ") +
         (errno != 0 ? std::strerror(errno) : "write error");
}

// Every failure ends here: one clear line, a documented exit code, never an uncaught exception.
int run_reporting_errors(const std::function<int()>& run) {
  int code = 0;
  try {
    code = run();
  } catch (const rtmot::InputError& error) {
    spdlog::error("{}", error.what());
    return rtmot::to_int(error.exit_code());
  } catch (const std::exception& error) {
    // fmt::print throws when stdout refuses a write larger than its buffer.
    if (const std::string failure = stdout_failure(); !failure.empty()) {
      spdlog::error("{}", failure);
      return rtmot::to_int(rtmot::ExitCode::io_error);
    }
    spdlog::critical("internal error: {}", error.what());
    return rtmot::to_int(rtmot::ExitCode::internal_error);
  }
  if (const std::string failure = stdout_failure(); !failure.empty()) {
    spdlog::error("{}", failure);
    if (code == 0) code = rtmot::to_int(rtmot::ExitCode::io_error);
  }
  return code;
}

// SIGINT/SIGTERM (and SIGHUP) blocked before anything else, so that a command that stops cleanly on
// them takes the ones sent while it starts (platform::StopSignals sigwait()s pending signals too).
// main() is too late: the constructors of the ~250 shared libraries (OpenCV, GStreamer, ...) run
// before it, 60-200 ms during which SIGTERM killed `rtmot run`. A .preinit_array entry of the
// executable runs after the loader has mapped the libraries and before any of their constructors;
// the process is single-threaded then, so sigprocmask is the whole mask. SIGXFSZ is ignored here
// too: under a file-size limit (ulimit -f, systemd's LimitFSIZE=) its default action killed the run
// mid-record; ignored, the write fails with EFBIG and the output is cut back to its last whole
// record (common/output_file.cpp) and the run ends with io_error.
void block_stop_signals(int, char**, char**) {
  std::signal(SIGXFSZ, SIG_IGN);
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGHUP);  // `run` re-reads its configuration on it (platform/signals)
  sigprocmask(SIG_BLOCK, &stop_signals, nullptr);
}
__attribute__((section(".preinit_array"),
               used)) void (*const block_at_start)(int, char**, char**) = &block_stop_signals;

// For commands that do not stop cleanly: a pending or later signal takes its default action.
void unblock_stop_signals() {
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGHUP);
  pthread_sigmask(SIG_UNBLOCK, &stop_signals, nullptr);
}

// --log-format json as the command line asks for it, read before CLI11 parses it: a command-line
// error (found by that parse) must be a JSON line too when a log shipper reads stderr.
bool asks_for_json_log(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") break;
    if (arg == "--log-format=json" ||
        (arg == "--log-format" && i + 1 < argc && std::string_view(argv[i + 1]) == "json")) {
      return true;
    }
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  // Logs and errors go to stderr (the journal on a board); stdout carries only command output.
  spdlog::set_default_logger(spdlog::stderr_color_mt("rtmot"));

  CLI::App app{"rtmot: real-time multiple-object tracking (SSD detector + SORT tracker)"};
  app.require_subcommand(1);
  // Global options (--log-level) are accepted after the subcommand too: subcommands created below
  // inherit fallthrough and hand options they do not know to this parser.
  app.fallthrough();
  app.set_version_flag("--version", "rtmot " RTMOT_VERSION);
  using rtmot::platform::kLogFormatNames;
  using rtmot::platform::kLogLevelNames;
  std::string log_level{kLogLevelNames.name(rtmot::platform::LogLevel::info)};
  // The accepted names are listed by the check (--help: "TEXT:trace, debug, ...").
  app.add_option("--log-level", log_level, "the least severe lines shown")
      ->check(rtmot::app::one_of(kLogLevelNames));
  std::string log_format{kLogFormatNames.name(rtmot::platform::LogFormat::text)};
  app.add_option("--log-format", log_format,
                 "json: one JSON object per line (time, level, thread, message) for log "
                 "shippers")
      ->check(rtmot::app::one_of(kLogFormatNames));
  std::string log_file;
  app.add_option("--log-file", log_file, "also append the log to this file");

  using namespace rtmot::app;
  const std::vector<Subcommand> subcommands = {
      // SUBCOMMAND-LIST
      add_count_command(app), add_eval_command(app),  add_listen_command(app),
      add_model_command(app), add_run_command(app),   add_soak_command(app),
      add_study_command(app), add_track_command(app),
  };

  if (asks_for_json_log(argc, argv)) {
    rtmot::platform::configure_logging(rtmot::platform::LogFormat::json, "");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
    spdlog::error("{}", rtmot::app::parse_error_line(app, argc, argv, error));
    return rtmot::to_int(rtmot::ExitCode::usage);
  }
  // Both were checked against their tables by the parser.
  const auto level = *kLogLevelNames.parse(log_level);
  const auto format = *kLogFormatNames.parse(log_format);
  rtmot::platform::set_log_level(level);
  if (format != rtmot::platform::LogFormat::text || !log_file.empty()) {
    try {
      rtmot::platform::configure_logging(format, log_file);
    } catch (const rtmot::InputError& error) {
      spdlog::error("{}", error.what());
      return rtmot::to_int(error.exit_code());
    }
  }
  // OpenCV's own warnings would surround our one error line with lines of its own: it speaks only
  // when asked for debug output.
  cv::utils::logging::setLogLevel(level <= rtmot::platform::LogLevel::debug
                                      ? cv::utils::logging::LOG_LEVEL_INFO
                                      : cv::utils::logging::LOG_LEVEL_SILENT);
  for (const auto& subcommand : subcommands) {
    if (!subcommand.cli->parsed()) continue;
    if (!subcommand.stops_on_signals) unblock_stop_signals();
    int code = run_reporting_errors(subcommand.run);
    // A log that could not be written (a full disk) does not stop a command, but a command that
    // succeeded says so at the end instead of exiting 0 with its log cut short.
    if (const std::string failure = rtmot::platform::log_file_failure();
        !failure.empty() && code == 0) {
      spdlog::error("{} (the log lines after it are lost)", failure);
      code = rtmot::to_int(rtmot::ExitCode::io_error);
    }
    return code;
  }
  return rtmot::to_int(rtmot::ExitCode::usage);
}
