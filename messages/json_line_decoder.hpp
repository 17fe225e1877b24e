#pragma once
// Reads back one JSON line as messages/jsonl_sink.cpp writes it (an MQTT `format=json` payload, a
// line of `--jsonl`): the inverse of append_json_line, so `rtmot listen` counts JSON boards like
// binary ones. Field names and meaning: docs/message-format.md, "JSON lines".
#include <cstddef>
#include <cstdint>
#include <string>

#include "messages/message_format.hpp"

namespace rtmot::messages {

/// True if `data` looks like a JSON object (first non-blank byte '{'); a binary message starts
/// with the magic "RTMT", so one look tells the two apart in a mixed subscription.
bool looks_like_json(const std::uint8_t* data, std::size_t size);

/// Decodes one JSON line from untrusted bytes into `out` (the same fields a binary message
/// carries; `out.version` = the line's schema). Returns false with `problem` set (one phrase
/// naming the field) if the text is not JSON, a required field is missing or has the wrong type,
/// or the schema is newer than this reader's. Never throws.
bool decode_json_line(const std::uint8_t* data, std::size_t size, DecodedMessage& out,
                      std::string& problem);

}  // namespace rtmot::messages
