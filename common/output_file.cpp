#include "common/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <string>
#include <utility>

#include "common/input_error.hpp"
#include "common/output_open.hpp"
#include "common/stale_temporaries.hpp"

namespace rtmot {
namespace {

// Publishing by rename replaces the directory entry: right for a regular file (or a new one), wrong
// for a device, a FIFO or a socket. Renaming over /dev/full as root replaced the device with a
// plain file; such targets are written in place.
OutputFile::Publish effective_publish(const std::filesystem::path& path,
                                      OutputFile::Publish wanted) {
  if (wanted != OutputFile::Publish::on_close) return wanted;
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status) || std::filesystem::is_regular_file(status)) {
    return wanted;
  }
  return OutputFile::Publish::as_written;
}

}  // namespace

OutputFile::OutputFile(std::filesystem::path path, Publish publish, std::size_t buffer_bytes)
    : path_(std::move(path)),
      publish_(effective_publish(path_, publish)),
      buffer_(std::max<std::size_t>(buffer_bytes, 1)) {
  record_ends_.reserve(1024);
  if (publish_ == Publish::on_close) {
    fd_ = create_temporary(path_);
    written_path_ = temporary_path_for(path_);
  } else {
    fd_ = open_output_in_place(
        path_, publish_ == Publish::appended ? OutputMode::append : OutputMode::truncate);
    written_path_ = path_;
  }
}

OutputFile::~OutputFile() {
  if (unpublished_) ::unlink(written_path_.c_str());  // finished, never published
  if (fd_ < 0) return;                                // closed or moved from
  if (publish_ != Publish::on_close) {
    try {
      flush();
    } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor cannot report; close() does
    }
  } else {
    ::unlink(written_path_.c_str());
  }
  if (fd_ >= 0) ::close(fd_);
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : path_(std::move(other.path_)),
      written_path_(std::move(other.written_path_)),
      publish_(other.publish_),
      fd_(std::exchange(other.fd_, -1)),
      unpublished_(std::exchange(other.unpublished_, false)),
      buffer_(std::move(other.buffer_)),
      used_(std::exchange(other.used_, 0)),
      record_ends_(std::move(other.record_ends_)) {}

void OutputFile::write(const void* data, std::size_t size) {
  if (fd_ < 0) throw InputError(path_.string(), 0, "", "write after close");
  if (used_ + size > buffer_.size()) flush();
  if (size > buffer_.size()) {
    write_out(static_cast<const char*>(data), size, {size});  // alone: one record, one write()
    return;
  }
  std::memcpy(buffer_.data() + used_, data, size);
  used_ += size;
  record_ends_.push_back(used_);  // no allocation once it has held a buffer's worth
}

void OutputFile::flush() {
  if (fd_ < 0 || used_ == 0) return;
  const std::size_t size = used_;
  used_ = 0;
  try {
    write_out(buffer_.data(), size, record_ends_);
  } catch (...) {
    record_ends_.clear();
    throw;
  }
  record_ends_.clear();
}

void OutputFile::write_out(const char* data, std::size_t size,
                           const std::vector<std::size_t>& record_ends) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t wrote = ::write(fd_, data + done, size - done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) {
      const int error = wrote < 0 ? errno : ENOSPC;
      // Cut back to the end of the last whole record, so that what stays readable is whole. The
      // file's offset is where `done` ended (appended files too: others may have written before).
      const auto whole = std::upper_bound(record_ends.begin(), record_ends.end(), done);
      const std::size_t torn = done - (whole == record_ends.begin() ? 0 : *std::prev(whole));
      const off_t end = ::lseek(fd_, 0, SEEK_CUR);
      if (end >= static_cast<off_t>(torn) &&
          ::ftruncate(fd_, end - static_cast<off_t>(torn)) == 0) {
        ::lseek(fd_, end - static_cast<off_t>(torn), SEEK_SET);
      }
      fail("cannot write", error);
    }
    done += static_cast<std::size_t>(wrote);
  }
}

void OutputFile::finish_writing() {
  if (fd_ < 0) return;
  flush();
  // A published file must be on the disk before its name is: a crash after the rename must not
  // leave an empty file under the final name.
  if (publish_ == Publish::on_close && ::fsync(fd_) != 0) fail("cannot write", errno);
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) {
    const int error = errno;
    if (publish_ == Publish::on_close) ::unlink(written_path_.c_str());
    throw InputError(path_.string(), 0, "", std::string("cannot write: ") + std::strerror(error),
                     ExitCode::io_error);
  }
  unpublished_ = publish_ == Publish::on_close;
}

void OutputFile::publish() {
  if (!unpublished_) return;
  unpublished_ = false;
  if (::rename(written_path_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    ::unlink(written_path_.c_str());
    throw InputError(path_.string(), 0, "", std::string("cannot rename: ") + std::strerror(error),
                     ExitCode::io_error);
  }
}

void OutputFile::fail(const char* action, int error) {
  throw InputError(path_.string(), 0, "", std::string(action) + ": " + std::strerror(error),
                   ExitCode::io_error);
}

void write_whole_file(const std::filesystem::path& path, std::string_view text) {
  OutputFile file(path, OutputFile::Publish::on_close, 0);
  file.write(text);
  file.close();
}

void publish_together(OutputFile& first, OutputFile& second) {
  first.finish_writing();
  second.finish_writing();
  first.publish();
  second.publish();
}

}  // namespace rtmot
