#pragma once
// A log message as the content of a JSON string (--log-format json): what spdlog's own %v does not
// do. A message holds what the user named (file names, URIs), and a Linux file name is bytes, not
// text: a byte that is not part of well-formed UTF-8 would make the line invalid JSON (a log
// shipper drops or rejects it), so it is written as the four characters \xNN (JSON "\\xNN"), which
// keep the name recoverable; '"', '\' and control characters are escaped as JSON requires.
#include <string>
#include <string_view>

namespace rtmot::platform {

/// Appends `text` to `out` as JSON string content (without the quotes), always valid UTF-8.
void append_json_string_content(std::string_view text, std::string& out);

}  // namespace rtmot::platform
