#pragma once
// `mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json]`: where an MQTT publisher sends and what
// `rtmot listen --mqtt` subscribes to (there TOPIC may hold the wildcards + and #).
#include <cstdint>
#include <optional>
#include <string>

namespace rtmot::outputs {

enum class MqttPayload { binary, json };

struct MqttUri {
  std::string host;
  std::uint16_t port{1883};
  std::string topic;
  int qos{1};
  MqttPayload payload{MqttPayload::binary};
};

/// Parses `text`; nullopt with `problem` set (one phrase) if malformed. HOST:PORT goes through
/// platform::parse_host_port, so `mqtt://[::1]:1883/t` works.
std::optional<MqttUri> parse_mqtt_uri(const std::string& text, std::string& problem);

/// The URI back as text (for logs).
std::string to_string(const MqttUri& uri);

}  // namespace rtmot::outputs
