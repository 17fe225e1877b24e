#include "outputs/mqtt_publisher.hpp"

#include <mosquitto.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace rtmot::outputs {
namespace {

std::string default_client_id(std::uint32_t stream_id) {
  return "rtmot-" + std::to_string(stream_id) + "-" + std::to_string(::getpid());
}

}  // namespace

MqttPublisher::MqttPublisher(MqttPublisherOptions options, std::uint32_t stream_id,
                             messages::ClassLabelFn labels)
    : options_(std::move(options)),
      stream_id_(stream_id),
      labels_(labels),
      queue_(options_.queue_capacity,
             [](Item& item) { item.bytes.resize(messages::message::max_message_size); }),
      client_(options_.client_id.empty() ? default_client_id(stream_id) : options_.client_id,
              this) {
  mosquitto_connect_callback_set(client_.handle(), &MqttPublisher::on_connect);
  mosquitto_disconnect_callback_set(client_.handle(), &MqttPublisher::on_disconnect);
  mosquitto_publish_callback_set(client_.handle(), &MqttPublisher::on_publish);
  // libmosquitto's own in-flight window matches ours, so it never queues a QoS 1 message itself.
  mosquitto_int_option(client_.handle(), MOSQ_OPT_SEND_MAXIMUM, options_.max_in_flight);
  client_.start(options_.uri, options_.reconnect);
  publisher_ = std::thread([this] { publish_loop(); });
}

MqttPublisher::~MqttPublisher() {
  queue_.close();
  {
    const std::lock_guard<std::mutex> lock(state_mutex_);
    stopping_.store(true, std::memory_order_release);
  }
  state_changed_.notify_all();
  publisher_.join();
  client_.stop();
}

void MqttPublisher::write(const messages::FrameResult& result) {
  Item* item = queue_.try_claim();
  if (item == nullptr) {
    counters_.dropped.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (options_.uri.payload == MqttPayload::json) {
    json_.clear();
    messages::append_json_line(result, static_cast<std::uint32_t>(result.tracks.size()), false,
                               messages::JsonLineExtras{messages::wall_now_ns(), &labels_}, json_);
    // Without the newline: one message is one JSON object. Grows the slot only for a line longer
    // than any before (the slot keeps its capacity).
    item->size = json_.size() - 1;
    if (item->bytes.size() < item->size) item->bytes.resize(item->size);
    std::memcpy(item->bytes.data(), json_.data(), item->size);
  } else {
    item->size = encoder_.encode(result, item->bytes.data(), item->bytes.size());
  }
  counters_.queued.fetch_add(1, std::memory_order_relaxed);
  queue_.publish();
}

bool MqttPublisher::wait_until_sendable() {
  std::unique_lock<std::mutex> lock(state_mutex_);
  state_changed_.wait(lock, [this] {
    return stopping_.load(std::memory_order_acquire) ||
           (connected_.load(std::memory_order_acquire) &&
            in_flight_.load(std::memory_order_acquire) < options_.max_in_flight);
  });
  return !stopping_.load(std::memory_order_acquire);
}

void MqttPublisher::publish_loop() {
  while (Item* item = queue_.front(stopping_)) {
    if (!wait_until_sendable()) break;
    in_flight_.fetch_add(1, std::memory_order_acq_rel);
    const int rc = mosquitto_publish(client_.handle(), nullptr, options_.uri.topic.c_str(),
                                     static_cast<int>(item->size), item->bytes.data(),
                                     options_.uri.qos, false);
    if (rc != MOSQ_ERR_SUCCESS) {
      const bool connection_gone = rc == MOSQ_ERR_NO_CONN || rc == MOSQ_ERR_CONN_LOST;
      if (connection_gone) {
        // The connection dropped between the check and the call.
        const std::lock_guard<std::mutex> lock(state_mutex_);
        connected_.store(false, std::memory_order_release);
      }
      if (connection_gone && options_.uri.qos > 0) {
        // libmosquitto queued a QoS 1 message before it found the connection gone
        // (lib/messages_mosq.c: message__queue, then send): it sends it again after the
        // reconnect and its acknowledgement comes through on_publish, so the message stays in
        // flight. Publishing it again would deliver it twice (seen: 5001 acknowledgements for
        // 5000 messages and a duplicate at the listener when the broker restarted mid-run).
        queue_.pop();
        continue;
      }
      in_flight_.fetch_sub(1, std::memory_order_acq_rel);
      if (connection_gone) continue;  // QoS 0 is not queued: keep the item for the reconnect
      spdlog::warn("mqtt {}: publish failed: {}", options_.uri.topic, mosquitto_error_text(rc));
      counters_.failed.fetch_add(1, std::memory_order_release);
    }
    queue_.pop();
  }
}

void MqttPublisher::flush() {
  std::unique_lock<std::mutex> lock(state_mutex_);
  const bool done = state_changed_.wait_for(lock, options_.flush_timeout, [this] {
    return counters_.published.load(std::memory_order_acquire) +
                   counters_.failed.load(std::memory_order_acquire) >=
               counters_.queued.load(std::memory_order_acquire) &&
           in_flight_.load(std::memory_order_acquire) == 0;
  });
  if (!done) {
    spdlog::warn(
        "mqtt {}: {} of {} messages not yet {} after {} ms (broker away?)", to_string(options_.uri),
        counters_.queued.load() - std::min(counters_.queued.load(), counters_.published.load()),
        counters_.queued.load(), options_.uri.qos == 1 ? "acknowledged" : "sent",
        options_.flush_timeout.count());
  }
}

void MqttPublisher::on_connect(struct mosquitto*, void* self, int rc) {
  auto& publisher = *static_cast<MqttPublisher*>(self);
  if (rc != 0) {
    spdlog::warn("mqtt {}: broker refused the connection: {}", to_string(publisher.options_.uri),
                 mosquitto_connack_string(rc));
    return;
  }
  publisher.counters_.connects.fetch_add(1, std::memory_order_relaxed);
  {
    const std::lock_guard<std::mutex> lock(publisher.state_mutex_);
    publisher.connected_.store(true, std::memory_order_release);
  }
  publisher.state_changed_.notify_all();
}

void MqttPublisher::on_disconnect(struct mosquitto*, void* self, int rc) {
  auto& publisher = *static_cast<MqttPublisher*>(self);
  {
    const std::lock_guard<std::mutex> lock(publisher.state_mutex_);
    publisher.connected_.store(false, std::memory_order_release);
  }
  if (rc != 0) {  // 0: our own disconnect at the end
    publisher.counters_.disconnects.fetch_add(1, std::memory_order_relaxed);
    if (publisher.counters_.connects.load(std::memory_order_relaxed) > 0) {
      spdlog::warn("mqtt {}: connection lost; reconnecting with backoff",
                   to_string(publisher.options_.uri));
    } else if (!publisher.unreached_logged_) {  // libmosquitto's thread only
      publisher.unreached_logged_ = true;
      spdlog::warn("mqtt {}: cannot reach the broker ({}); retrying with backoff",
                   to_string(publisher.options_.uri), mosquitto_strerror(rc));
    }
  }
  publisher.state_changed_.notify_all();
}

void MqttPublisher::on_publish(struct mosquitto*, void* self, int) {
  auto& publisher = *static_cast<MqttPublisher*>(self);
  {
    const std::lock_guard<std::mutex> lock(publisher.state_mutex_);
    publisher.counters_.published.fetch_add(1, std::memory_order_acq_rel);
    publisher.in_flight_.fetch_sub(1, std::memory_order_acq_rel);
  }
  publisher.state_changed_.notify_all();
}

}  // namespace rtmot::outputs
