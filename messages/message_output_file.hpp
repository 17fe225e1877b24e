#pragma once
// An output file for the file sinks: RAII over stdio (its buffering is what we want, and errno
// tells why a write failed), every failure an rtmot::InputError that names the file.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace rtmot::messages {

class MessageOutputFile {
 public:
  /// Creates or truncates `path`; throws InputError (bad_input) naming it if it cannot.
  explicit MessageOutputFile(std::filesystem::path path);
  /// Flushes and closes; a failure here is logged, never thrown.
  ~MessageOutputFile();
  MessageOutputFile(MessageOutputFile&&) noexcept = default;
  MessageOutputFile& operator=(MessageOutputFile&&) noexcept = default;

  /// Buffered write; throws InputError naming the file (e.g. disk full) if the stream failed.
  void write(const void* data, std::size_t size);
  void flush();
  const std::filesystem::path& path() const { return path_; }

 private:
  struct Closer {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  [[noreturn]] void fail(const char* action, int error) const;

  std::filesystem::path path_;
  std::unique_ptr<std::FILE, Closer> file_;
};

}  // namespace rtmot::messages
