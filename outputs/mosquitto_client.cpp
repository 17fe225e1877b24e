#include "outputs/mosquitto_client.hpp"

#include <mosquitto.h>
#include <spdlog/spdlog.h>

#include "common/input_error.hpp"
#include "platform/host_port.hpp"

namespace rtmot::outputs {
namespace {

// mosquitto_lib_init is not thread-safe and must run once before any client: a function-local
// static runs it exactly once (C++11 guarantees thread-safe initialisation) and cleans up at exit.
struct MosquittoLibrary {
  MosquittoLibrary() { mosquitto_lib_init(); }
  ~MosquittoLibrary() { mosquitto_lib_cleanup(); }
  MosquittoLibrary(const MosquittoLibrary&) = delete;
  MosquittoLibrary& operator=(const MosquittoLibrary&) = delete;
};

void ensure_library() {
  static const MosquittoLibrary library;
}

constexpr int keepalive_s = 10;  // a dead broker is noticed within 1.5 keepalives

}  // namespace

std::string mosquitto_error_text(int code) {
  return mosquitto_strerror(code);
}

MosquittoClient::MosquittoClient(const std::string& client_id, void* user_data) {
  ensure_library();
  client_ = mosquitto_new(client_id.c_str(), true, user_data);
  if (client_ == nullptr) {
    throw InputError("mqtt", 0, "", "cannot create an MQTT client (out of memory?)",
                     ExitCode::network);
  }
  mosquitto_int_option(client_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
}

MosquittoClient::~MosquittoClient() {
  stop();
  mosquitto_destroy(client_);
}

void MosquittoClient::start(const MqttUri& uri, MqttReconnect reconnect) {
  mosquitto_reconnect_delay_set(client_, static_cast<unsigned>(reconnect.min_delay.count()),
                                static_cast<unsigned>(reconnect.max_delay.count()), true);
  const std::string where = "mqtt://" + platform::format_host_port(uri.host, uri.port);
  // The loop thread first, then the connection: libmosquitto's loop thread retries a connection
  // that failed with its reconnect backoff only when it is already running when connect_async
  // fails (started after a failed connect_async, it gives up: a broker started after the board
  // would never be reached).
  const int looping = mosquitto_loop_start(client_);
  if (looping != MOSQ_ERR_SUCCESS) {
    throw InputError(where, 0, "", "cannot start the MQTT thread: " + mosquitto_error_text(looping),
                     ExitCode::network);
  }
  started_ = true;
  const int connected = mosquitto_connect_async(client_, uri.host.c_str(), uri.port, keepalive_s);
  if (connected == MOSQ_ERR_EAI || connected == MOSQ_ERR_INVAL) {
    stop();
    throw InputError(where, 0, "", "cannot resolve the broker's host", ExitCode::network);
  }
  if (connected != MOSQ_ERR_SUCCESS) {
    spdlog::warn("{}: broker not reachable yet ({}); retrying in the background", where,
                 mosquitto_error_text(connected));
  }
}

void MosquittoClient::stop() {
  if (!started_) return;
  started_ = false;
  mosquitto_disconnect(client_);
  // Not forced (that would pthread_cancel a thread running C++): the disconnect above wakes the
  // loop thread even from its reconnect sleep, and it ends on the disconnecting state.
  mosquitto_loop_stop(client_, false);
}

}  // namespace rtmot::outputs
