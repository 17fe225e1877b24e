#include "runner/web_geometry.hpp"

#include "common/utf8.hpp"

namespace rtmot::runner {

nlohmann::json web_geometry(const events::EventsConfig& events, std::uint32_t stream_id,
                            const std::string& uri, int width, int height) {
  const auto point = [](const events::Point& p) { return nlohmann::json::array({p.x, p.y}); };
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& line : events.lines) {
    lines.push_back({{"name", replace_invalid_utf8(line.name)},
                     {"from", point(line.segment.from)},
                     {"to", point(line.segment.to)},
                     {"in", line.in_is_left ? "left" : "right"}});
  }
  nlohmann::json zones = nlohmann::json::array();
  for (const auto& zone : events.zones) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : zone.polygon) points.push_back(point(p));
    zones.push_back({{"name", replace_invalid_utf8(zone.name)}, {"points", points}});
  }
  return {{"stream", stream_id}, {"uri", replace_invalid_utf8(uri)},
          {"width", width},      {"height", height},
          {"lines", lines},      {"zones", zones}};
}

}  // namespace rtmot::runner
