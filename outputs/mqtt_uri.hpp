#pragma once
// `mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json]`: where an MQTT publisher sends and what
// `rtmot listen --mqtt` subscribes to (there TOPIC may hold the wildcards + and #).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "tracker/enum_names.hpp"

namespace rtmot::outputs {

enum class MqttPayload { binary, json };
/// The one table of payload names: the URI's `format=` values.
inline constexpr auto kMqttPayloadNames = tracker::make_enum_names<MqttPayload>(
    std::pair{MqttPayload::binary, std::string_view("binary")},
    std::pair{MqttPayload::json, std::string_view("json")});

struct MqttUri {
  std::string host;
  std::uint16_t port{1883};
  std::string topic;
  int qos{1};
  MqttPayload payload{MqttPayload::binary};
};

/// What the topic is for: a publisher's topic name may hold no wildcard; a subscriber's filter may
/// hold + (a whole level) and # (a whole last level).
enum class MqttTopicUse { publish, subscribe };

/// Parses `text`; nullopt with `problem` set (one phrase) if malformed. HOST:PORT goes through
/// platform::parse_host_port, so `mqtt://[::1]:1883/t` works. The topic follows the MQTT
/// specification's rules for `use` (well-formed UTF-8 without NUL or control characters, at most
/// 65535 bytes, wildcards only whole levels of a filter) and a topic name for publishing does not
/// start with '$' (the broker's own, $SYS): checked here, at start, because a topic the broker
/// refuses failed every message later (30 warnings a second) or subscribed to nothing.
std::optional<MqttUri> parse_mqtt_uri(const std::string& text, std::string& problem,
                                      MqttTopicUse use = MqttTopicUse::publish);

/// "" when `topic` is valid for `use` (the rules above), else why not.
std::string check_mqtt_topic(const std::string& topic, MqttTopicUse use);

/// "mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json]", the formats from kMqttPayloadNames:
/// for help texts, errors and docs/config.md.
std::string mqtt_uri_syntax();

/// The URI back as text (for logs).
std::string to_string(const MqttUri& uri);

}  // namespace rtmot::outputs
