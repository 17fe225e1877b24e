#include "run_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace rtmot::test {

namespace {

#ifdef RTMOT_SANITIZED
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// In the child between fork and exec: async-signal-safe calls only.
[[noreturn]] void exec_child(char* const* args, const char* cwd, const char* out_path,
                             const char* stdout_device, const char* err_path,
                             std::uint64_t file_size_limit, std::uint64_t address_space_limit) {
  if (::chdir(cwd) != 0) ::_exit(126);
  const int in = ::open("/dev/null", O_RDONLY);
  const int out = stdout_device != nullptr ? ::open(stdout_device, O_WRONLY)
                                           : ::open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int err = ::open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (in < 0 || out < 0 || err < 0) ::_exit(126);
  ::dup2(in, STDIN_FILENO);
  ::dup2(out, STDOUT_FILENO);
  ::dup2(err, STDERR_FILENO);
  if (file_size_limit > 0) {
    // SIGXFSZ keeps its default action (kill): rtmot must ignore it itself, as a service under
    // systemd's LimitFSIZE= or a shell's `ulimit -f` would see it.
    const rlimit limit{file_size_limit, file_size_limit};
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  if (address_space_limit > 0 && !kSanitized) {
    const rlimit limit{address_space_limit, address_space_limit};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  sigset_t none;  // the test runner may block signals; the child starts as a shell would start it
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::execve(args[0], args, environ);
  ::_exit(127);
}

}  // namespace

std::string rtmot_binary() {
  const char* other = std::getenv("RTMOT_CATALOGUE_BINARY");
  return other != nullptr && *other != '\0' ? other : RTMOT_BINARY;
}

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                          std::chrono::seconds time_limit) {
  ProcessConditions conditions;
  conditions.time_limit = time_limit;
  return run_process(argv, cwd, conditions);
}

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                          const ProcessConditions& conditions) {
  // Output goes to files rather than pipes: no risk of a full pipe blocking the child. They are
  // opened before the file-size limit applies.
  const std::string out_path = (cwd / ".stdout").string();
  const std::string err_path = (cwd / ".stderr").string();
  const std::string dir = cwd.string();
  std::vector<char*> args;
  for (const auto& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);

  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + argv[0]);
  if (pid == 0) {
    exec_child(args.data(), dir.c_str(), out_path.c_str(),
               conditions.stdout_device.empty() ? nullptr : conditions.stdout_device.c_str(),
               err_path.c_str(), conditions.file_size_limit, conditions.address_space_limit);
  }

  ProcessResult result;
  const auto deadline = start + conditions.time_limit;
  std::size_t next_signal = 0;
  auto armed_at = start;  // when the next signal's condition was met
  bool armed = false;
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, WNOHANG, &usage) == 0) {
    const auto now = std::chrono::steady_clock::now();
    if (next_signal < conditions.signals.size()) {
      const TimedSignal& next = conditions.signals[next_signal];
      const bool fallback = next.fallback.count() > 0 && now - start >= next.fallback;
      // file_size() answers -1 with an error code when the file is not there yet.
      std::error_code no_file;
      const auto written =
          next.after_file.empty() ? 0 : std::filesystem::file_size(next.after_file, no_file);
      const bool file_written = next.after_file.empty() || (!no_file && written > 0);
      if (!armed && file_written &&
          (next.after_output.empty() || fallback ||
           slurp(out_path).find(next.after_output) != std::string::npos ||
           slurp(err_path).find(next.after_output) != std::string::npos)) {
        armed = true;
        armed_at = now;
      }
      if (armed && now - armed_at >= next.delay) {
        ::kill(pid, next.signal);
        ++next_signal;
        armed = false;
        continue;
      }
    }
    if (now > deadline) {
      result.timed_out = true;
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  result.max_rss_kb = usage.ru_maxrss;
  if (!result.timed_out && WIFEXITED(status)) {
    result.exited = true;
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  if (conditions.stdout_device.empty()) result.out = slurp(out_path);
  result.err = slurp(err_path);
  return result;
}

}  // namespace rtmot::test
