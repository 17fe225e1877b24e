// The MQTT publisher and subscriber against Debian's mosquitto, started here on a free loopback
// port: QoS 1 and 0, binary and JSON payloads, a broker absent at start-up (the bounded queue
// counts what it drops, then delivers when the broker appears), and a broker restarted mid-run.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "message_test_data.hpp"
#include "messages/message_format.hpp"
#include "mosquitto_broker.hpp"
#include "outputs/mqtt_publisher.hpp"
#include "outputs/mqtt_subscriber.hpp"
#include "scratch_folder.hpp"

namespace rtmot::outputs {
namespace {

using namespace std::chrono_literals;

// Everything a subscriber received, decoded.
class Received {
 public:
  void add(const std::uint8_t* payload, std::size_t size) {
    const std::lock_guard<std::mutex> lock(mutex_);
    raw_.emplace_back(payload, payload + size);
  }
  std::size_t count() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return raw_.size();
  }
  std::vector<std::vector<std::uint8_t>> take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return raw_;
  }
  bool wait_for_count(std::size_t wanted, std::chrono::milliseconds limit) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (count() < wanted && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(10ms);
    }
    return count() >= wanted;
  }

 private:
  std::mutex mutex_;
  std::vector<std::vector<std::uint8_t>> raw_;
};

MqttUri uri_of(const std::string& text, MqttTopicUse use = MqttTopicUse::publish) {
  std::string problem;
  const auto uri = parse_mqtt_uri(text, problem, use);
  EXPECT_TRUE(uri.has_value()) << text << ": " << problem;
  return uri.value_or(MqttUri{});
}

bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!done() && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(10ms);
  return done();
}

class Mqtt : public ::testing::Test {
 protected:
  test::ScratchFolder scratch_{"mqtt"};  // removed when the test passed
  std::filesystem::path folder_ = scratch_.path();
};

TEST(MqttUri, ReadsBrokerTopicQosAndFormat) {
  const MqttUri uri = uri_of("mqtt://[::1]:1884/fleet/board7?qos=0&format=json");
  EXPECT_EQ(uri.host, "::1");
  EXPECT_EQ(uri.port, 1884);
  EXPECT_EQ(uri.topic, "fleet/board7");
  EXPECT_EQ(uri.qos, 0);
  EXPECT_EQ(uri.payload, MqttPayload::json);
  EXPECT_EQ(uri_of("mqtt://broker/t").port, 1883);
  EXPECT_EQ(uri_of("mqtt://broker/t").qos, 1);
  std::string problem;
  EXPECT_FALSE(parse_mqtt_uri("mqtt://broker", problem));
  EXPECT_EQ(problem, "missing /TOPIC after the broker's address");
  EXPECT_FALSE(parse_mqtt_uri("mqtt://broker/t?qos=2", problem));
  EXPECT_EQ(problem, "qos must be 0 or 1, got '2'");
  EXPECT_FALSE(parse_mqtt_uri("mqtt://broker:99999/t", problem));
  EXPECT_EQ(problem, "port 99999 is out of range 1..65535");
  EXPECT_FALSE(parse_mqtt_uri("udp://broker/t", problem));
}

// The payload formats are kMqttPayloadNames: each name is read, written back by to_string, and an
// unknown one is refused with the table's names.
TEST(MqttUri, FormatsAreTheTablesNames) {
  for (const auto& [payload, name] : kMqttPayloadNames.entries()) {
    SCOPED_TRACE(std::string(name));
    const MqttUri uri = uri_of("mqtt://broker/t?format=" + std::string(name));
    EXPECT_EQ(uri.payload, payload);
    EXPECT_EQ(to_string(uri), "mqtt://broker:1883/t?qos=1&format=" + std::string(name));
    EXPECT_EQ(uri_of(to_string(uri)).payload, payload);
  }
  std::string problem;
  EXPECT_FALSE(parse_mqtt_uri("mqtt://broker/t?format=xml", problem));
  EXPECT_EQ(problem, "format must be binary or json, got 'xml'");
  EXPECT_EQ(mqtt_uri_syntax(), "mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json]");
}

// Issue 23, class 9: the MQTT specification's rules, checked at start for the topic's use.
TEST(MqttTopics, AreCheckedForTheirUse) {
  using Use = MqttTopicUse;
  EXPECT_EQ(check_mqtt_topic("fleet/board7/tracks", Use::publish), "");
  EXPECT_EQ(check_mqtt_topic("fleet/+/tracks", Use::subscribe), "");
  EXPECT_EQ(check_mqtt_topic("fleet/#", Use::subscribe), "");
  EXPECT_EQ(check_mqtt_topic("#", Use::subscribe), "");
  EXPECT_EQ(check_mqtt_topic("$SYS/broker/uptime", Use::subscribe), "");
  EXPECT_NE(check_mqtt_topic("fleet/+/tracks", Use::publish).find("wildcards"), std::string::npos);
  EXPECT_NE(check_mqtt_topic("fleet/#", Use::publish).find("wildcards"), std::string::npos);
  EXPECT_NE(check_mqtt_topic("$SYS/x", Use::publish).find("$SYS"), std::string::npos);
  for (const char* filter : {"a/b#", "a/#/b", "a/b+/c", "+a"}) {
    EXPECT_NE(check_mqtt_topic(filter, Use::subscribe).find("not a topic filter"),
              std::string::npos)
        << filter;
  }
  for (const Use use : {Use::publish, Use::subscribe}) {
    EXPECT_NE(check_mqtt_topic("", use), "");
    EXPECT_NE(check_mqtt_topic("caf\xE9", use).find("UTF-8"), std::string::npos);
    EXPECT_NE(check_mqtt_topic(std::string("a\0b", 3), use).find("UTF-8"), std::string::npos);
    EXPECT_NE(check_mqtt_topic("a\x01b", use).find("UTF-8"), std::string::npos);
    EXPECT_NE(check_mqtt_topic(std::string(65536, 'a'), use).find("65535"), std::string::npos);
  }
  std::string problem;
  EXPECT_FALSE(parse_mqtt_uri("mqtt://broker/a/+", problem));
  EXPECT_TRUE(parse_mqtt_uri("mqtt://broker/a/+", problem, Use::subscribe)) << problem;
}

TEST_F(Mqtt, Qos1DeliversEveryMessageIntact) {
  test::MosquittoBroker broker(folder_);
  Received received;
  MqttSubscriber subscriber(
      uri_of(broker.mqtt_uri("rtmot/#"), MqttTopicUse::subscribe),
      [&](const std::uint8_t* data, std::size_t size) { received.add(data, size); });
  ASSERT_TRUE(wait_until([&] { return subscriber.subscriptions() == 1; }, 10s));

  const auto frames = test::frames_from_detections("ETH-Bahnhof", 300);
  MqttPublisherOptions options;
  options.uri = uri_of(broker.mqtt_uri("rtmot/board1?qos=1"));
  // The 300 frames come as one burst, far faster than a camera: room for all of them.
  options.queue_capacity = frames.size();
  {
    MqttPublisher publisher(options, 1);
    ASSERT_TRUE(wait_until([&] { return publisher.connected(); }, 10s));
    for (const auto& frame : frames) publisher.write(frame);
    publisher.flush();
    EXPECT_EQ(publisher.counters().queued.load(), frames.size());
    EXPECT_EQ(publisher.counters().published.load(), frames.size());
    EXPECT_EQ(publisher.counters().dropped.load(), 0U);
  }
  ASSERT_TRUE(received.wait_for_count(frames.size(), 10s)) << received.count();
  const auto payloads = received.take();
  messages::DecodedMessage decoded;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_EQ(messages::decode_message(payloads[i].data(), payloads[i].size(), decoded),
              messages::DecodeError::none);
    EXPECT_TRUE(test::same_as_sent(frames[i], decoded));  // and in order
  }
}

TEST_F(Mqtt, Qos0JsonPayloadsAreJsonObjects) {
  test::MosquittoBroker broker(folder_);
  Received received;
  MqttSubscriber subscriber(
      uri_of(broker.mqtt_uri("rtmot/json?qos=0")),
      [&](const std::uint8_t* data, std::size_t size) { received.add(data, size); });
  ASSERT_TRUE(wait_until([&] { return subscriber.subscriptions() == 1; }, 10s));
  const auto frames = test::frames_from_detections("TUD-Campus", 50);
  MqttPublisherOptions options;
  options.uri = uri_of(broker.mqtt_uri("rtmot/json?qos=0&format=json"));
  {
    MqttPublisher publisher(options, 4,
                            [](int id) -> std::string_view { return id == 1 ? "person" : ""; });
    ASSERT_TRUE(wait_until([&] { return publisher.connected(); }, 10s));
    for (const auto& frame : frames) publisher.write(frame);
    publisher.flush();
  }
  // QoS 0 on loopback with a broker that keeps up: nothing is lost in practice.
  ASSERT_TRUE(received.wait_for_count(frames.size(), 10s)) << received.count();
  const auto payloads = received.take();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto json = nlohmann::json::parse(payloads[i].begin(), payloads[i].end());
    EXPECT_EQ(json.at("frame").get<std::int64_t>(), frames[i].frame_number);
    EXPECT_EQ(json.at("schema").get<int>(), messages::json_schema_version);
    ASSERT_EQ(json.at("tracks").size(), frames[i].tracks.size());
    if (!frames[i].tracks.empty()) {
      EXPECT_EQ(json.at("tracks")[0].at("label").get<std::string>(), "person");
    }
  }
}

// A board that starts before its broker: write() never waits; the bounded queue keeps the first
// `capacity` messages and counts the rest as dropped; when the broker appears, the kept ones go
// out.
TEST_F(Mqtt, BrokerAbsentAtStartQueueBoundedThenDelivered) {
  test::MosquittoBroker broker(folder_);
  broker.stop();
  MqttPublisherOptions options;
  options.uri = uri_of(broker.mqtt_uri("rtmot/late"));
  options.queue_capacity = 64;
  const auto frames = test::frames_from_detections("PETS09-S2L1", 200);
  MqttPublisher publisher(options, 9);
  for (const auto& frame : frames) publisher.write(frame);
  EXPECT_FALSE(publisher.connected());
  EXPECT_EQ(publisher.counters().queued.load(), 64U);
  EXPECT_EQ(publisher.counters().dropped.load(), frames.size() - 64);
  EXPECT_EQ(publisher.counters().published.load(), 0U);

  broker.start();
  // The reconnect backoff may still be waiting; it connects within its max delay, and the broker
  // acknowledges every message that was held.
  ASSERT_TRUE(wait_until([&] { return publisher.counters().published.load() == 64; }, 30s))
      << publisher.counters().published.load();
  EXPECT_EQ(publisher.counters().connects.load(), 1U);
}

TEST_F(Mqtt, BrokerRestartIsRiddenOut) {
  test::MosquittoBroker broker(folder_);
  Received received;
  MqttSubscriber subscriber(
      uri_of(broker.mqtt_uri("rtmot/restart")),
      [&](const std::uint8_t* data, std::size_t size) { received.add(data, size); });
  ASSERT_TRUE(wait_until([&] { return subscriber.subscriptions() == 1; }, 10s));
  MqttPublisherOptions options;
  options.uri = uri_of(broker.mqtt_uri("rtmot/restart"));
  const auto frames = test::frames_from_detections("ETH-Sunnyday", 300);
  MqttPublisher publisher(options, 2);
  ASSERT_TRUE(wait_until([&] { return publisher.connected(); }, 10s));
  for (std::size_t i = 0; i < 100; ++i) publisher.write(frames[i]);
  publisher.flush();
  ASSERT_TRUE(received.wait_for_count(100, 10s));

  broker.stop();
  ASSERT_TRUE(wait_until([&] { return !publisher.connected(); }, 10s));
  for (std::size_t i = 100; i < 200; ++i) publisher.write(frames[i]);  // held in the queue
  EXPECT_EQ(publisher.counters().dropped.load(), 0U);
  broker.start();
  ASSERT_TRUE(wait_until([&] { return subscriber.subscriptions() == 2; }, 30s));
  ASSERT_TRUE(wait_until([&] { return publisher.connected(); }, 30s));
  for (std::size_t i = 200; i < 300; ++i) publisher.write(frames[i]);
  publisher.flush();
  EXPECT_EQ(publisher.counters().published.load(), 300U);
  EXPECT_GE(publisher.counters().disconnects.load(), 1U);
  EXPECT_GE(publisher.counters().connects.load(), 2U);
  // The last message arrives (publishing resumed); what the restart cost is what the broker
  // accepted while the subscriber had not yet subscribed again.
  ASSERT_TRUE(wait_until(
      [&] {
        const auto payloads = received.take();
        messages::DecodedMessage decoded;
        return !payloads.empty() &&
               messages::decode_message(payloads.back().data(), payloads.back().size(), decoded) ==
                   messages::DecodeError::none &&
               decoded.frame.sequence == frames[299].sequence;
      },
      10s));
  EXPECT_GE(received.count(), 200U);
}

}  // namespace
}  // namespace rtmot::outputs
