#pragma once
// Reads what BinaryFileSink wrote: length-prefixed messages. Trusts nothing in the file.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/input_file.hpp"

namespace rtmot::messages {

enum class FileReadStatus {
  message,        // `bytes` holds one message (still to be decoded: it may be corrupt)
  end_of_file,    // clean end, after a whole record
  broken_framing  // a cut record or an impossible length: what follows cannot be found again
};

class MessageFileReader {
 public:
  /// Throws InputError (bad_input) naming `path` if it cannot be opened or is not a regular file
  /// (a FIFO would block forever). A failed read throws InputError (io_error).
  explicit MessageFileReader(const std::filesystem::path& path);

  FileReadStatus next(std::vector<std::uint8_t>& bytes);
  /// Why framing broke, naming the record and its byte offset (the caller names the file).
  const std::string& problem() const { return problem_; }
  std::uint64_t records_read() const { return records_; }

 private:
  FileReadStatus broken(const std::string& what);

  InputFile file_;
  std::uint64_t offset_{0};
  std::uint64_t records_{0};
  std::string problem_;
};

}  // namespace rtmot::messages
