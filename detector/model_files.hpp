#pragma once
// The detector's files (model, anchors, checksums) are read through common/input_file like every
// other input (regular files only, a size bound, read errors are errors); here are their bounds
// and the one translation of its errors to the model's exit code.
#include <cstdint>
#include <filesystem>
#include <string>

#include "common/input_file.hpp"

namespace rtmot::detector {

/// An SSD is tens of MB; a file far beyond is a mistake, refused before it fills memory.
constexpr std::uint64_t kMaxModelBytes = 1ULL << 30;
/// 1917 anchors are 89 KB.
constexpr std::uint64_t kMaxAnchorsBytes = 16ULL << 20;
/// A few lines of "SHA256  NAME".
constexpr std::uint64_t kMaxChecksumBytes = 1ULL << 20;

/// The whole file. Throws InputError: ExitCode::bad_model naming the file and `what` (with the way
/// out) when it is missing, not a regular file (folder, FIFO, device) or over `max_bytes`;
/// ExitCode::io_error on a read error.
/// `remedy` is the way out the message gives.
std::string read_model_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                            const std::string& what,
                            const std::string& remedy = "run scripts/fetch_model.sh");

/// The file opened for reading, under the same rules.
InputFile open_model_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                          const std::string& what);

}  // namespace rtmot::detector
