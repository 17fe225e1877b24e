#pragma once
// What the web page draws over a source's picture (docs/web.md, /api/status "geometry"): the
// frame's size and the lines and zones counted on it, in pixels.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "events/events_config.hpp"

namespace rtmot::runner {

nlohmann::json web_geometry(const events::EventsConfig& events, std::uint32_t stream_id,
                            const std::string& uri, int width, int height);

}  // namespace rtmot::runner
