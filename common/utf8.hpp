#pragma once
// UTF-8 as RFC 3629 defines it: what a text read from a user's file must be before it goes where
// UTF-8 is required (a Prometheus label value, a JSON string). Overlong forms, surrogates and code
// points above U+10FFFF are invalid, as are a lead byte without its continuation bytes and a stray
// continuation byte.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace rtmot {

/// The byte offset of the first byte that does not start a valid UTF-8 sequence; nullopt when
/// all of `text` is valid.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

/// `text` with every byte that does not start a valid sequence replaced by U+FFFD.
std::string replace_invalid_utf8(std::string_view text);

}  // namespace rtmot
