#pragma once
// One libmosquitto client, RAII: the library is initialised once per process (before the first
// client) and each client's network thread is stopped and the client destroyed with its owner.
// Connection state and reconnection with exponential backoff are libmosquitto's own (its loop
// thread reconnects after a lost connection, waiting min_delay, doubling up to max_delay).
#include <chrono>
#include <memory>
#include <string>

#include "outputs/mqtt_uri.hpp"

struct mosquitto;

namespace rtmot::outputs {

struct MqttReconnect {
  std::chrono::seconds min_delay{1};  // libmosquitto counts in whole seconds
  std::chrono::seconds max_delay{16};
};

class MosquittoClient {
 public:
  /// Creates a client with a clean session and `client_id` (unique per broker). `user_data` is
  /// handed to the callbacks set on handle(). Throws InputError (ExitCode::network) on failure.
  MosquittoClient(const std::string& client_id, void* user_data);
  ~MosquittoClient();
  MosquittoClient(const MosquittoClient&) = delete;
  MosquittoClient& operator=(const MosquittoClient&) = delete;

  /// Starts the network thread and connects in the background: a broker that is not up yet is
  /// retried with the reconnect backoff, so a board can start before its broker. Call once, after
  /// the callbacks are set. Throws InputError only for what cannot get better (bad host name).
  void start(const MqttUri& uri, MqttReconnect reconnect);
  /// Disconnects cleanly and joins the network thread (also done by the destructor).
  void stop();

  mosquitto* handle() const { return client_; }

 private:
  mosquitto* client_{nullptr};
  bool started_{false};
};

/// libmosquitto's text for an error code (MOSQ_ERR_*).
std::string mosquitto_error_text(int code);

}  // namespace rtmot::outputs
