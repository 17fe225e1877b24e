#include "mosquitto_broker.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>

namespace rtmot::test {

MosquittoBroker::MosquittoBroker(const std::filesystem::path& folder)
    : folder_(folder), port_(free_tcp_port()) {
  std::filesystem::create_directories(folder_);
  std::ofstream config(folder_ / "mosquitto.conf");
  config << "listener " << port_ << " 127.0.0.1\nallow_anonymous true\n"
         << "max_queued_messages 100000\n";
  config.close();
  start();
}

void MosquittoBroker::start() {
  process_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"mosquitto", "-c", (folder_ / "mosquitto.conf").string()},
      folder_ / "broker.out", folder_ / "broker.err");
  ASSERT_TRUE(process_->running()) << "is Debian's mosquitto installed (scripts/install_deps.sh)?";
  ASSERT_TRUE(wait_for_tcp(port_, std::chrono::seconds(10)))
      << "mosquitto did not listen on 127.0.0.1:" << port_ << ": "
      << read_text(folder_ / "broker.err");
}

void MosquittoBroker::stop() {
  if (process_) process_->stop(SIGTERM, std::chrono::seconds(10));
  process_.reset();
}

std::string MosquittoBroker::mqtt_uri(const std::string& topic) const {
  return "mqtt://127.0.0.1:" + std::to_string(port_) + "/" + topic;
}

}  // namespace rtmot::test
