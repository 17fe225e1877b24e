#include "outputs/mqtt_uri.hpp"

#include <mosquitto.h>

#include <string_view>

#include "platform/host_port.hpp"

namespace rtmot::outputs {
namespace {

constexpr std::string_view scheme = "mqtt://";
constexpr std::uint16_t default_port = 1883;

bool read_parameter(std::string_view key, std::string_view value, MqttUri& uri,
                    std::string& problem) {
  if (key == "qos") {
    if (value != "0" && value != "1") {
      problem = "qos must be 0 or 1, got '" + std::string(value) + "'";
      return false;
    }
    uri.qos = value == "1" ? 1 : 0;
    return true;
  }
  if (key == "format") {
    const auto payload = kMqttPayloadNames.parse(value);
    if (!payload) {
      problem = "format must be " + kMqttPayloadNames.alternatives() + ", got '" +
                std::string(value) + "'";
      return false;
    }
    uri.payload = *payload;
    return true;
  }
  problem = "unknown parameter '" + std::string(key) + "' (qos, format)";
  return false;
}

}  // namespace

// libmosquitto's own checks (the ones its publish and subscribe apply), so that the start-up check
// and the library agree; control characters are refused by its UTF-8 check too.
std::string check_mqtt_topic(const std::string& topic, MqttTopicUse use) {
  if (topic.empty()) return "the topic is empty";
  if (topic.size() > 65535) return "the topic is longer than 65535 bytes";
  if (mosquitto_validate_utf8(topic.data(), static_cast<int>(topic.size())) != MOSQ_ERR_SUCCESS) {
    return "the topic is not valid UTF-8 or holds a NUL or control character";
  }
  if (use == MqttTopicUse::publish) {
    if (mosquitto_pub_topic_check2(topic.data(), topic.size()) != MOSQ_ERR_SUCCESS) {
      return "a topic to publish to may not hold the wildcards + or #, got '" + topic + "'";
    }
    if (topic.front() == '$') {
      return "topics starting with '$' are the broker's own ($SYS), got '" + topic + "'";
    }
    return {};
  }
  if (mosquitto_sub_topic_check2(topic.data(), topic.size()) != MOSQ_ERR_SUCCESS) {
    return "'" + topic +
           "' is not a topic filter: + and # must each be a whole level, # only the last";
  }
  return {};
}

std::optional<MqttUri> parse_mqtt_uri(const std::string& text, std::string& problem,
                                      MqttTopicUse use) {
  const std::string_view all(text);
  if (all.substr(0, scheme.size()) != scheme) {
    problem = "expected mqtt://HOST[:PORT]/TOPIC";
    return std::nullopt;
  }
  std::string_view rest = all.substr(scheme.size());
  const auto query_start = rest.find('?');
  const std::string_view query =
      query_start == std::string_view::npos ? std::string_view() : rest.substr(query_start + 1);
  rest = rest.substr(0, query_start);
  const auto slash = rest.find('/');
  if (slash == std::string_view::npos || slash + 1 == rest.size()) {
    problem = "missing /TOPIC after the broker's address";
    return std::nullopt;
  }
  const auto address = platform::parse_host_port(rest.substr(0, slash), problem, default_port);
  if (!address) return std::nullopt;
  MqttUri uri;
  uri.host = address->host;
  uri.port = address->port;
  uri.topic = std::string(rest.substr(slash + 1));
  problem = check_mqtt_topic(uri.topic, use);
  if (!problem.empty()) return std::nullopt;
  std::string_view parameters = query;
  while (!parameters.empty()) {
    const auto amp = parameters.find('&');
    const std::string_view pair = parameters.substr(0, amp);
    const auto equals = pair.find('=');
    if (equals == std::string_view::npos) {
      problem = "parameter '" + std::string(pair) + "' has no '=VALUE'";
      return std::nullopt;
    }
    if (!read_parameter(pair.substr(0, equals), pair.substr(equals + 1), uri, problem)) {
      return std::nullopt;
    }
    parameters = amp == std::string_view::npos ? std::string_view() : parameters.substr(amp + 1);
  }
  return uri;
}

std::string mqtt_uri_syntax() {
  std::string formats;
  for (const auto& entry : kMqttPayloadNames.entries()) {
    formats += (formats.empty() ? "" : "|") + std::string(entry.second);
  }
  return "mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=" + formats + "]";
}

std::string to_string(const MqttUri& uri) {
  return "mqtt://" + platform::format_host_port(uri.host, uri.port) + "/" + uri.topic +
         "?qos=" + std::to_string(uri.qos) +
         "&format=" + std::string(kMqttPayloadNames.name(uri.payload));
}

}  // namespace rtmot::outputs
