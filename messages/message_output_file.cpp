#include "messages/message_output_file.hpp"

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "common/input_error.hpp"

namespace rtmot::messages {

MessageOutputFile::MessageOutputFile(std::filesystem::path path)
    : path_(std::move(path)), file_(std::fopen(path_.c_str(), "wb")) {
  if (!file_) fail("cannot create", errno);
}

MessageOutputFile::~MessageOutputFile() {
  if (!file_) return;  // moved from
  const bool flushed = std::fflush(file_.get()) == 0;
  const int error = errno;
  const bool closed = std::fclose(file_.release()) == 0;
  if (!flushed || !closed) {
    spdlog::error("{}: cannot flush/close: {}", path_.string(),
                  std::strerror(flushed ? errno : error));
  }
}

void MessageOutputFile::write(const void* data, std::size_t size) {
  if (size > 0 && std::fwrite(data, 1, size, file_.get()) != size) fail("cannot write", errno);
}

void MessageOutputFile::flush() {
  if (std::fflush(file_.get()) != 0) fail("cannot flush", errno);
}

void MessageOutputFile::fail(const char* action, int error) const {
  throw InputError(path_.string(), 0, "", std::string(action) + ": " + std::strerror(error));
}

}  // namespace rtmot::messages
