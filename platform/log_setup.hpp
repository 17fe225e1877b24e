#pragma once
// Where and how rtmot logs: stderr (the journal on a board) as text, or one JSON object per line
// for log shippers (--log-format json), and optionally also a file (--log-file).
#include <string>

namespace rtmot::platform {

enum class LogFormat { text, json };

/// Replaces the default logger "rtmot": stderr, plus `file` (appended) when not empty, in
/// `format`. JSON lines: {"time":"...Z","level":"info","thread":N,"message":"..."}, the message
/// escaped. Throws InputError (io_error) naming the file if it cannot be opened.
void configure_logging(LogFormat format, const std::string& file);

}  // namespace rtmot::platform
