#pragma once
// Subscribes to an MQTT topic (filter: + and # allowed) and hands every message's payload to a
// callback, on libmosquitto's network thread. Resubscribes after each reconnection (a restarted
// broker has forgotten the subscription); reconnects with libmosquitto's exponential backoff.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "outputs/mosquitto_client.hpp"
#include "outputs/mqtt_uri.hpp"

struct mosquitto;
struct mosquitto_message;

namespace rtmot::outputs {

class MqttSubscriber {
 public:
  /// Called on libmosquitto's thread, one message at a time.
  using Handler = std::function<void(const std::uint8_t* payload, std::size_t size)>;

  MqttSubscriber(const MqttUri& uri, Handler handler, MqttReconnect reconnect = {});
  ~MqttSubscriber() = default;
  MqttSubscriber(const MqttSubscriber&) = delete;
  MqttSubscriber& operator=(const MqttSubscriber&) = delete;

  /// Subscriptions the broker acknowledged (one per connection).
  std::uint64_t subscriptions() const { return subscriptions_.load(std::memory_order_acquire); }
  std::uint64_t disconnects() const { return disconnects_.load(std::memory_order_relaxed); }
  /// Why the subscription failed (libmosquitto refused it, or the broker's SUBACK did), or "".
  /// A listener subscribed to nothing would run forever receiving nothing: the caller ends.
  std::string failure() const {
    return failed_.load(std::memory_order_acquire) ? failure_ : std::string();
  }

 private:
  static void on_connect(mosquitto* client, void* self, int rc);
  static void on_disconnect(mosquitto*, void* self, int rc);
  static void on_subscribe(mosquitto*, void* self, int, int granted_count, const int* granted);
  void fail(std::string why);
  static void on_message(mosquitto*, void* self, const mosquitto_message* message);

  MqttUri uri_;
  Handler handler_;
  std::atomic<std::uint64_t> subscriptions_{0};
  std::atomic<std::uint64_t> disconnects_{0};
  // failure_ is written once, by the thread that wins failure_claimed_, before failed_ is set with
  // release; failure() reads it only after an acquire of failed_.
  std::atomic<bool> failure_claimed_{false};
  std::string failure_;
  std::atomic<bool> failed_{false};
  MosquittoClient client_;  // last: stopped (and its thread joined) before the rest goes
};

}  // namespace rtmot::outputs
