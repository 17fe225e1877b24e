#pragma once
// The one way rtmot opens a file it reads. Only regular files: a FIFO would block forever, a
// directory reads as nothing and a device (/dev/zero) never ends, and each of those used to be
// taken for an empty or endless input. Read errors (EIO) are reported, never taken for the end.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace rtmot {

/// Largest text file (configuration, seqinfo.ini, det/gt/results) read whole: MOT20's biggest
/// det.txt is ~50 MB; a larger one is a mistake (or /proc/...), refused before it fills memory.
constexpr std::uint64_t kMaxTextFileBytes = 512ULL << 20;

/// A regular file open for reading (RAII over the descriptor).
class InputFile {
 public:
  /// Throws InputError (bad_input) naming `path` if it is missing, unreadable, or not a regular
  /// file (a folder, FIFO, socket or device), and if it is larger than `max_bytes`.
  explicit InputFile(std::filesystem::path path, std::uint64_t max_bytes = UINT64_MAX);
  ~InputFile();
  InputFile(InputFile&& other) noexcept;
  InputFile& operator=(InputFile&& other) noexcept;
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Reads up to `size` bytes; fewer only at the end of the file. Throws InputError (io_error) on
  /// a failed read.
  std::size_t read(void* data, std::size_t size);
  /// Moves `bytes` forward without reading them (the caller keeps within size()). Throws
  /// InputError (io_error) when the file cannot seek.
  void skip(std::uint64_t bytes);
  /// The size when it was opened.
  std::uint64_t size() const { return size_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_{-1};
  std::uint64_t size_{0};
};

/// "" when `path` is a regular file that opens for reading, else why not ("cannot open file: no
/// such file", "is a FIFO (pipe), expected a regular file"): for a file a library opens itself
/// (GStreamer's filesrc), checked first by the same rules.
std::string input_file_problem(const std::filesystem::path& path);

/// A whole regular file (at most `max_bytes`: a file that grows beyond it while being read is
/// refused too).
std::string read_text_file(const std::filesystem::path& path,
                           std::uint64_t max_bytes = kMaxTextFileBytes);

}  // namespace rtmot
