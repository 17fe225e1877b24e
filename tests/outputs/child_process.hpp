#pragma once
// A program the test starts in the background (a broker, a listener, an RTSP client) and stops:
// its stdout and stderr go to files the test reads afterwards.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace rtmot::test {

class ChildProcess {
 public:
  /// Starts argv[0] (searched in PATH) with stdout/stderr redirected to the given files. Fails the
  /// test (ADD_FAILURE) and leaves running() false if it cannot start.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& out_file,
               const std::filesystem::path& err_file);
  /// Kills (SIGKILL) and reaps the child if it is still running.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool running() const { return pid_ > 0; }
  /// Sends `signal` and waits up to `limit` for the child to end; returns its exit status as
  /// waitpid gives it, or -1 if it had to be killed.
  int stop(int signal, std::chrono::milliseconds limit);
  /// Waits up to `limit` for the child to end by itself; -1 (and kills it) if it did not.
  int wait(std::chrono::milliseconds limit);

 private:
  pid_t pid_{-1};
};

/// A TCP port on 127.0.0.1 that was free a moment ago (bound to port 0, read back, released).
unsigned short free_tcp_port();
/// Waits up to `limit` until something accepts TCP connections on 127.0.0.1:port.
bool wait_for_tcp(unsigned short port, std::chrono::milliseconds limit);
/// The whole content of a file ("" if absent).
std::string read_text(const std::filesystem::path& path);

}  // namespace rtmot::test
