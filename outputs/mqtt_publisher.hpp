#pragma once
// Publishes every track message to an MQTT broker (output.mqtt / --mqtt), binary (the UDP
// datagram's bytes) or JSON lines, at QoS 0 or 1.
//
// Never blocks the sink stage: write() encodes into a slot of a bounded lock-free SPSC queue
// (pipeline/spsc_queue.hpp) and returns; when the queue is full (broker away longer than the queue
// lasts, or slower than the frame rate) the message is dropped and counted. A publisher thread
// takes the queue's items and hands them to libmosquitto only while connected and, at QoS 1, while
// fewer than max_in_flight messages await the broker's PUBACK: so libmosquitto's own (unbounded)
// queue never grows, and the bounded one is the only buffer. libmosquitto reconnects with
// exponential backoff; messages in flight when the connection dropped are sent again (QoS 1).
#include <fmt/format.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "messages/frame_result.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/message_format.hpp"
#include "outputs/mosquitto_client.hpp"
#include "outputs/mqtt_uri.hpp"
#include "pipeline/spsc_queue.hpp"

namespace rtmot::outputs {

struct MqttPublisherOptions {
  MqttUri uri;
  std::string client_id;            // empty: "rtmot-<stream id>-<pid>"
  std::size_t queue_capacity{256};  // messages held while the broker is away (~8 s at 30 fps)
  int max_in_flight{32};            // QoS 1 messages sent but not yet acknowledged
  MqttReconnect reconnect;
  std::chrono::milliseconds flush_timeout{5000};  // flush() waits this long for the broker
};

/// Counters, readable from any thread (relaxed atomics: statistics, not synchronisation).
struct MqttPublisherCounters {
  std::atomic<std::uint64_t> queued{0};     // accepted by write()
  std::atomic<std::uint64_t> dropped{0};    // refused by write(): queue full
  std::atomic<std::uint64_t> published{0};  // QoS 0: handed to the socket; QoS 1: acknowledged
  std::atomic<std::uint64_t> failed{0};     // refused by libmosquitto (logged), not retried
  std::atomic<std::uint64_t> connects{0};   // successful (re)connections
  std::atomic<std::uint64_t> disconnects{0};
};

class MqttPublisher final : public messages::TrackSink {
 public:
  /// Starts the client and its threads; a broker that is not up yet is retried in the background.
  MqttPublisher(MqttPublisherOptions options, std::uint32_t stream_id,
                messages::ClassLabelFn labels = nullptr);
  ~MqttPublisher() override;
  MqttPublisher(const MqttPublisher&) = delete;
  MqttPublisher& operator=(const MqttPublisher&) = delete;

  /// The sink stage's call: encodes into the queue or counts a drop. No lock, no system call
  /// unless the publisher thread sleeps (then one futex wake).
  void write(const messages::FrameResult& result) override;
  /// Waits up to flush_timeout for the queue to drain and (QoS 1) every message to be acknowledged;
  /// logs what is still pending after that rather than blocking shutdown forever.
  void flush() override;

  const MqttPublisherCounters& counters() const { return counters_; }
  bool connected() const { return connected_.load(std::memory_order_acquire); }
  const MqttPublisherOptions& options() const { return options_; }

 private:
  struct Item {
    std::vector<std::uint8_t> bytes;
    std::size_t size{0};
  };
  static void on_connect(mosquitto*, void* self, int rc);
  static void on_disconnect(mosquitto*, void* self, int rc);
  static void on_publish(mosquitto*, void* self, int mid);
  void publish_loop();
  /// Waits until the item may be handed to libmosquitto (connected, room in flight) or stopping.
  bool wait_until_sendable();

  MqttPublisherOptions options_;
  std::uint32_t stream_id_;
  messages::ClassLabelFn labels_;
  MqttPublisherCounters counters_;
  // Sink stage only.
  messages::MessageEncoder encoder_;
  fmt::memory_buffer json_;
  // Between the sink stage (producer) and the publisher thread (consumer).
  pipeline::SpscQueue<Item> queue_;
  std::atomic<bool> stopping_{false};
  // Publisher thread and libmosquitto's thread: state changes wake the publisher. Off the sink
  // stage's path, so a mutex is fine here.
  std::atomic<bool> connected_{false};
  std::atomic<int> in_flight_{0};
  bool unreached_logged_{false};  // libmosquitto's thread only: "cannot reach" is said once
  std::mutex state_mutex_;
  std::condition_variable state_changed_;
  MosquittoClient client_;
  std::thread publisher_;
};

}  // namespace rtmot::outputs
