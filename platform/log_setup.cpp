#include "platform/log_setup.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "common/input_error.hpp"
#include "common/output_file.hpp"
#include "platform/json_log_text.hpp"

namespace rtmot::platform {
namespace {

// %* in the pattern: the message as JSON string content (platform/json_log_text.hpp).
class JsonMessage final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& message, const std::tm&,
              spdlog::memory_buf_t& out) override {
    text_.clear();
    append_json_string_content(std::string_view(message.payload.data(), message.payload.size()),
                               text_);
    out.append(text_.data(), text_.data() + text_.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<JsonMessage>();
  }

 private:
  std::string text_;
};

std::unique_ptr<spdlog::formatter> make_formatter(LogFormat format) {
  if (format == LogFormat::text) {
    return std::make_unique<spdlog::pattern_formatter>();  // spdlog's default, as before
  }
  auto formatter = std::make_unique<spdlog::pattern_formatter>(spdlog::pattern_time_type::utc);
  formatter->add_flag<JsonMessage>('*').set_pattern(
      R"({"time":"%Y-%m-%dT%H:%M:%S.%eZ","level":"%l","thread":%t,"message":"%*"})");
  return formatter;
}

// The --log-file: held until the command has checked it against its inputs, then an OutputFile
// (appended, each line one write(), a failed write cut back to the last whole line). A write that
// fails ends the file's lines (the first failure is kept for main() to report) but never the
// command: the run is worth more than its log.
class LogFileSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit LogFileSink(std::string path) : path_(std::move(path)) {}

  const std::string& path() const { return path_; }

  void open() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (file_) return;
    file_.emplace(path_, OutputFile::Publish::appended, 0);
    if (dropped_ > 0)
      held_ += fmt::format("({} earlier log lines dropped: more than 1 MiB)\n", dropped_);
    write_line(held_);
    held_.clear();
    held_.shrink_to_fit();
  }

  std::string failure() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
  }

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override {
    spdlog::memory_buf_t formatted;
    formatter_->format(message, formatted);
    const std::string_view line(formatted.data(), formatted.size());
    if (file_) {
      write_line(line);
    } else if (held_.size() + line.size() <= kMaxHeldBytes) {
      held_.append(line);
    } else {
      ++dropped_;
    }
  }
  void flush_() override {}  // every line is written at once

 private:
  static constexpr std::size_t kMaxHeldBytes = 1 << 20;

  void write_line(std::string_view line) {
    if (!failure_.empty() || line.empty()) return;
    try {
      file_->write(line);
    } catch (const InputError& error) {
      failure_ = error.what();
    }
  }

  std::string path_;
  std::optional<OutputFile> file_;
  std::string held_;
  std::size_t dropped_{0};
  std::string failure_;
};

std::shared_ptr<LogFileSink> log_file_sink() {
  for (const auto& sink : spdlog::default_logger()->sinks()) {
    if (auto file = std::dynamic_pointer_cast<LogFileSink>(sink)) return file;
  }
  return nullptr;
}

}  // namespace

void set_log_level(LogLevel level) {
  switch (level) {
    case LogLevel::trace:
      return spdlog::set_level(spdlog::level::trace);
    case LogLevel::debug:
      return spdlog::set_level(spdlog::level::debug);
    case LogLevel::info:
      return spdlog::set_level(spdlog::level::info);
    case LogLevel::warn:
      return spdlog::set_level(spdlog::level::warn);
    case LogLevel::error:
      return spdlog::set_level(spdlog::level::err);
    case LogLevel::off:
      return spdlog::set_level(spdlog::level::off);
  }
}

void configure_logging(LogFormat format, const std::string& file) {
  std::vector<spdlog::sink_ptr> sinks{std::make_shared<spdlog::sinks::stderr_color_sink_mt>()};
  if (!file.empty()) sinks.push_back(std::make_shared<LogFileSink>(file));
  auto logger = std::make_shared<spdlog::logger>("rtmot", sinks.begin(), sinks.end());
  logger->set_formatter(make_formatter(format));
  logger->set_level(spdlog::get_level());
  // Errors are written at once: a service killed after an error has it in the file.
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(logger);
}

void check_files_and_open_log(std::vector<NamedFile> inputs, std::vector<NamedFile> outputs) {
  const auto log = log_file_sink();
  if (log) outputs.push_back({log->path(), "--log-file"});
  check_distinct_files(inputs, outputs);
  if (log) log->open();
}

std::string log_file_failure() {
  const auto log = log_file_sink();
  return log ? log->failure() : std::string();
}

}  // namespace rtmot::platform
