#pragma once
// Where and how rtmot logs: stderr (the journal on a board) as text, or one JSON object per line
// for log shippers (--log-format json), and optionally also a file (--log-file).
#include <string>
#include <string_view>
#include <vector>

#include "common/distinct_files.hpp"
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
/// escaped (platform/json_log_text.hpp). The file is not opened here: it is an output like any
/// other, and may not name an input (appending to the configuration broke the next run) until
/// the command has checked it (check_files_and_open_log). Until then its lines are held in
/// memory (at most 1 MiB) and written when it opens; a command that fails before that point has
/// its error on stderr only.
void configure_logging(LogFormat format, const std::string& file);

/// What every command calls before it writes anything: check_distinct_files(inputs, outputs and
/// the --log-file), then opens the log file (common/output_open.hpp: a FIFO no process reads is
/// refused, not waited for) and writes the lines held so far. Throws InputError (bad_input).
void check_files_and_open_log(std::vector<NamedFile> inputs, std::vector<NamedFile> outputs);

/// The first failure to write the log file ("PATH: cannot write: No space left on device"), or ""
/// if none: the lines after it are lost, and main() ends a command that succeeded with io_error
/// and this line. A failed write is cut back to the last whole line.
std::string log_file_failure();

}  // namespace rtmot::platform
