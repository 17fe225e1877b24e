#include "detector/onnx_metadata.hpp"

#include <array>
#include <optional>

#include "common/input_error.hpp"
#include "common/input_file.hpp"

namespace rtmot::detector {
namespace {

// Hand-written on purpose: the ONNX library is optional in this product (only the XNNPACK engine
// needs it), and parsing a ModelProto would copy every weight of an 18 MB model to read a few
// bytes. ModelProto's top-level fields are scanned in protobuf's wire format and the graph is
// skipped with a seek. Field numbers from onnx.proto (ModelProto.metadata_props = 14;
// StringStringEntryProto.key = 1, .value = 2).
constexpr std::uint32_t kMetadataPropsField = 14;
constexpr std::uint32_t kEntryKeyField = 1;
constexpr std::uint32_t kEntryValueField = 2;
// Keys are short names; a longer one is not one this reader looks for.
constexpr std::uint64_t kMaxKeyBytes = 256;

enum WireType : std::uint32_t { varint = 0, fixed64 = 1, length_delimited = 2, fixed32 = 5 };

// Protobuf's wire format read from a regular file (common/input_file.hpp: a FIFO or a device is
// never opened for reading), buffered, with long fields skipped by seeking. `ok()` turns false on
// the first malformed or truncated field, and every read after that is a no-op.
class WireReader {
 public:
  explicit WireReader(InputFile& file) : file_(file) {}

  bool ok() const { return ok_; }
  std::uint64_t position() const { return position_; }
  bool at_end() const { return ok_ && position_ == file_.size(); }
  void fail() { ok_ = false; }

  std::uint64_t read_varint() {
    std::uint64_t value = 0;
    for (int shift = 0; ok_ && shift < 64; shift += 7) {
      const int byte = next_byte();
      if (byte < 0) break;
      value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    ok_ = false;
    return 0;
  }
  // Callers bound `length` first: it comes from the file.
  std::string read_bytes(std::uint64_t length) {
    if (!fits(length)) return {};
    std::string bytes;
    bytes.reserve(length);
    for (std::uint64_t i = 0; i < length; ++i) bytes += static_cast<char>(next_byte());
    return bytes;
  }
  void skip(std::uint64_t length) {
    if (!fits(length)) return;
    const std::uint64_t buffered = filled_ - next_;
    if (length <= buffered) {
      next_ += length;
    } else {
      file_.skip(length - buffered);
      next_ = filled_ = 0;
    }
    position_ += length;
  }
  // Skips the value of a field of `wire_type`; fails on a type no ONNX field uses (groups).
  void skip_value(std::uint32_t wire_type) {
    switch (wire_type) {
      case varint:
        read_varint();
        return;
      case fixed64:
        skip(8);
        return;
      case length_delimited:
        skip(read_varint());
        return;
      case fixed32:
        skip(4);
        return;
      default:
        ok_ = false;
    }
  }

 private:
  bool fits(std::uint64_t length) {
    if (ok_ && length > file_.size() - position_) ok_ = false;
    return ok_;
  }
  int next_byte() {
    if (next_ == filled_) {
      filled_ = file_.read(buffer_.data(), buffer_.size());
      next_ = 0;
      if (filled_ == 0) {
        ok_ = false;
        return -1;
      }
    }
    ++position_;
    return static_cast<unsigned char>(buffer_[next_++]);
  }

  InputFile& file_;
  std::array<char, 4096> buffer_{};
  std::size_t next_{0};
  std::size_t filled_{0};
  std::uint64_t position_{0};
  bool ok_{true};
};

struct Entry {
  std::string key;
  std::string value;
  bool value_too_long{false};
};

// One StringStringEntryProto of `length` bytes at the reader's position; values longer than
// `max_bytes` are skipped and flagged, so that a caller learns which key they belonged to.
Entry read_entry(WireReader& reader, std::uint64_t length, std::uint64_t max_bytes) {
  Entry entry;
  const std::uint64_t end = reader.position() + length;
  while (reader.ok() && reader.position() < end) {
    const std::uint64_t tag = reader.read_varint();
    const auto field = static_cast<std::uint32_t>(tag >> 3);
    const auto wire_type = static_cast<std::uint32_t>(tag & 7);
    if (wire_type != length_delimited || (field != kEntryKeyField && field != kEntryValueField)) {
      reader.skip_value(wire_type);
      continue;
    }
    const std::uint64_t size = reader.read_varint();
    const std::uint64_t limit = field == kEntryKeyField ? kMaxKeyBytes : max_bytes;
    if (size > limit) {
      reader.skip(size);
      if (field == kEntryValueField) entry.value_too_long = true;
      continue;
    }
    (field == kEntryKeyField ? entry.key : entry.value) = reader.read_bytes(size);
  }
  if (reader.ok() && reader.position() != end) reader.fail();
  return entry;
}

}  // namespace

std::optional<std::string> onnx_metadata_value(const std::filesystem::path& path,
                                               const std::string& key, std::uint64_t max_bytes) {
  std::optional<InputFile> file;
  try {
    file.emplace(path);
  } catch (const InputError&) {
    return std::nullopt;  // not a regular readable file: the network's loader says what it is
  }
  WireReader reader(*file);
  std::optional<std::string> found;
  while (!reader.at_end()) {
    const std::uint64_t tag = reader.read_varint();
    const auto field = static_cast<std::uint32_t>(tag >> 3);
    const auto wire_type = static_cast<std::uint32_t>(tag & 7);
    if (field == kMetadataPropsField && wire_type == length_delimited) {
      const std::uint64_t length = reader.read_varint();
      const Entry entry = read_entry(reader, length, max_bytes);
      if (!reader.ok()) return std::nullopt;
      if (entry.key == key && entry.value_too_long) {
        throw InputError(path.string(), 0, "metadata " + key,
                         "longer than " + std::to_string(max_bytes) + " bytes",
                         ExitCode::bad_model);
      }
      if (entry.key == key) found = entry.value;
    } else {
      reader.skip_value(wire_type);
    }
    if (!reader.ok()) return std::nullopt;
  }
  return found;
}

}  // namespace rtmot::detector
