#pragma once
// The model's integrity: scripts/fetch_model.sh writes `<model>.sha256` (sha256sum's format) beside
// the model; the detector checks the files it names before loading them, so a model damaged after
// download (disk, copy, hand edit) is refused with a clear error rather than giving wrong boxes.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

namespace rtmot::detector {

/// SHA-256 of a whole file, lower-case hex. Throws rtmot::InputError (ExitCode::bad_model) naming
/// the file when it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& path);

/// SHA-256 of a byte string, lower-case hex (tests and small inputs).
std::string sha256_hex(const std::string& bytes);

/// The checksum file that belongs to `model_path` (".onnx" replaced by ".sha256").
std::filesystem::path checksum_path_of(const std::filesystem::path& model_path);

/// When `checksum_file` exists, checks every file it lists that is `model_path` or `anchors_path`
/// (matched by file name, in the checksum file's folder) against its recorded SHA-256; files it
/// does not list are not checked. Returns how many files were checked (0 when there is no checksum
/// file). Throws rtmot::InputError (ExitCode::bad_model): naming the checksum file and line when a
/// line is malformed, naming the damaged file when a checksum differs.
int verify_model_checksums(const std::filesystem::path& checksum_file,
                           const std::filesystem::path& model_path,
                           const std::filesystem::path& anchors_path);

}  // namespace rtmot::detector
