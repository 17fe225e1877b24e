#include "outputs/mqtt_subscriber.hpp"

#include <mosquitto.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

namespace rtmot::outputs {

MqttSubscriber::MqttSubscriber(const MqttUri& uri, Handler handler, MqttReconnect reconnect)
    : uri_(uri),
      handler_(std::move(handler)),
      client_("rtmot-listen-" + std::to_string(::getpid()), this) {
  mosquitto_connect_callback_set(client_.handle(), &MqttSubscriber::on_connect);
  mosquitto_disconnect_callback_set(client_.handle(), &MqttSubscriber::on_disconnect);
  mosquitto_subscribe_callback_set(client_.handle(), &MqttSubscriber::on_subscribe);
  mosquitto_message_callback_set(client_.handle(), &MqttSubscriber::on_message);
  client_.start(uri_, reconnect);
}

void MqttSubscriber::on_connect(struct mosquitto* client, void* self, int rc) {
  auto& subscriber = *static_cast<MqttSubscriber*>(self);
  if (rc != 0) {
    spdlog::warn("{}: broker refused the connection: {}", to_string(subscriber.uri_),
                 mosquitto_connack_string(rc));
    return;
  }
  const int subscribed =
      mosquitto_subscribe(client, nullptr, subscriber.uri_.topic.c_str(), subscriber.uri_.qos);
  if (subscribed != MOSQ_ERR_SUCCESS) {
    subscriber.fail(std::string("cannot subscribe: ") + mosquitto_error_text(subscribed));
  }
}

void MqttSubscriber::fail(std::string why) {
  if (failure_claimed_.exchange(true, std::memory_order_acq_rel)) return;
  failure_ = std::move(why);
  failed_.store(true, std::memory_order_release);
}

void MqttSubscriber::on_disconnect(struct mosquitto*, void* self, int rc) {
  auto& subscriber = *static_cast<MqttSubscriber*>(self);
  if (rc == 0) return;  // our own disconnect at the end
  subscriber.disconnects_.fetch_add(1, std::memory_order_relaxed);
  spdlog::warn("{}: connection lost; reconnecting with backoff", to_string(subscriber.uri_));
}

void MqttSubscriber::on_subscribe(struct mosquitto*, void* self, int, int granted_count,
                                  const int* granted) {
  auto& subscriber = *static_cast<MqttSubscriber*>(self);
  // SUBACK's return code 0x80: the broker refused the filter (its ACL, or a filter it rejects).
  if (granted_count < 1 || granted == nullptr || granted[0] >= 0x80) {
    subscriber.fail("the broker refused the subscription");
    return;
  }
  subscriber.subscriptions_.fetch_add(1, std::memory_order_release);
  spdlog::info("subscribed to {}", to_string(subscriber.uri_));
}

void MqttSubscriber::on_message(struct mosquitto*, void* self,
                                const struct mosquitto_message* message) {
  auto& subscriber = *static_cast<MqttSubscriber*>(self);
  subscriber.handler_(static_cast<const std::uint8_t*>(message->payload),
                      static_cast<std::size_t>(message->payloadlen));
}

}  // namespace rtmot::outputs
