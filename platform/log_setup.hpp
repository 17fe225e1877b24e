#pragma once
// Where and how rtmot logs: stderr (the journal on a board) as text, or one JSON object per line
// for log shippers (--log-format json), and optionally also a file (--log-file).
#include <string>
#include <string_view>

#include "tracker/enum_names.hpp"

namespace rtmot::platform {

/// --log-level: the least severe kind of line shown, from the most verbose; off shows none.
enum class LogLevel { trace, debug, info, warn, error, off };
inline constexpr auto kLogLevelNames =
    tracker::make_enum_names<LogLevel>(std::pair{LogLevel::trace, std::string_view("trace")},
                                       std::pair{LogLevel::debug, std::string_view("debug")},
                                       std::pair{LogLevel::info, std::string_view("info")},
                                       std::pair{LogLevel::warn, std::string_view("warn")},
                                       std::pair{LogLevel::error, std::string_view("error")},
                                       std::pair{LogLevel::off, std::string_view("off")});

enum class LogFormat { text, json };
inline constexpr auto kLogFormatNames =
    tracker::make_enum_names<LogFormat>(std::pair{LogFormat::text, std::string_view("text")},
                                        std::pair{LogFormat::json, std::string_view("json")});

/// Sets the level of the default logger and of every logger made later (spdlog's global level).
void set_log_level(LogLevel level);

/// Replaces the default logger "rtmot": stderr, plus `file` (appended) when not empty, in
/// `format`. JSON lines: {"time":"...Z","level":"info","thread":N,"message":"..."}, the message
/// escaped. Throws InputError (io_error) naming the file if it cannot be opened.
void configure_logging(LogFormat format, const std::string& file);

}  // namespace rtmot::platform
