#pragma once
// Debian's mosquitto broker, started by the test on a free loopback port (config written to a
// temporary folder: loopback only, anonymous clients), stopped, and restarted on the same port.
#include <filesystem>
#include <memory>

#include "child_process.hpp"

namespace rtmot::test {

class MosquittoBroker {
 public:
  /// Starts it and waits until it accepts connections (fails the test if it does not).
  explicit MosquittoBroker(const std::filesystem::path& folder);
  unsigned short port() const { return port_; }
  /// SIGTERM, as an operator or systemd would stop it; waits for it to end.
  void stop();
  /// On the same port.
  void start();
  std::string mqtt_uri(const std::string& topic) const;

 private:
  std::filesystem::path folder_;
  unsigned short port_{0};
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace rtmot::test
