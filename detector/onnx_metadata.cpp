#include "detector/onnx_metadata.hpp"

#include <fstream>

#include "common/input_error.hpp"

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

enum WireType : std::uint32_t { varint = 0, fixed64 = 1, length_delimited = 2, fixed32 = 5 };

// A protobuf wire-format reader over a file; `ok()` turns false on the first
// malformed or truncated field, and every read after that is a no-op.
class WireReader {
 public:
  WireReader(std::istream& in, std::uint64_t size) : in_(in), size_(size) {}

  bool ok() const { return ok_; }
  bool at_end() { return ok_ && in_.peek() == std::char_traits<char>::eof(); }
  std::uint64_t read_varint() {
    std::uint64_t value = 0;
    for (int shift = 0; ok_ && shift < 64; shift += 7) {
      const int byte = in_.get();
      if (byte == std::char_traits<char>::eof()) break;
      value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    ok_ = false;
    return 0;
  }
  // Callers bound `length` first: it comes from the file.
  std::string read_bytes(std::uint64_t length) {
    std::string bytes(length, '\0');
    if (!in_.read(bytes.data(), static_cast<std::streamsize>(length))) ok_ = false;
    return bytes;
  }
  void fail() { ok_ = false; }
  // A seek past the end succeeds on a file: the size bounds it instead.
  void skip(std::uint64_t length) {
    const auto position = static_cast<std::uint64_t>(in_.tellg());
    if (!in_ || length > size_ - position) {
      ok_ = false;
      return;
    }
    in_.seekg(static_cast<std::streamoff>(length), std::ios::cur);
    if (!in_) ok_ = false;
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
  std::istream& in_;
  std::uint64_t size_;
  bool ok_{true};
};

// Keys are short names; a longer one is not one this reader looks for.
constexpr std::uint64_t kMaxKeyBytes = 256;

struct Entry {
  std::string key;
  std::string value;
  bool value_too_long{false};
};

// One StringStringEntryProto of `length` bytes at the reader's position; values longer than
// `max_bytes` are skipped and flagged, so that a caller learns which key they belonged to.
Entry read_entry(WireReader& reader, std::istream& in, std::uint64_t length,
                 std::uint64_t max_bytes) {
  Entry entry;
  const std::streamoff end =
      static_cast<std::streamoff>(in.tellg()) + static_cast<std::streamoff>(length);
  while (reader.ok() && static_cast<std::streamoff>(in.tellg()) < end) {
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
  if (reader.ok() && static_cast<std::streamoff>(in.tellg()) != end) reader.fail();
  return entry;
}

}  // namespace

std::optional<std::string> onnx_metadata_value(const std::filesystem::path& path,
                                               const std::string& key, std::uint64_t max_bytes) {
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (error || !in) return std::nullopt;
  WireReader reader(in, size);
  std::optional<std::string> found;
  while (!reader.at_end()) {
    const std::uint64_t tag = reader.read_varint();
    const auto field = static_cast<std::uint32_t>(tag >> 3);
    const auto wire_type = static_cast<std::uint32_t>(tag & 7);
    if (field == kMetadataPropsField && wire_type == length_delimited) {
      const std::uint64_t length = reader.read_varint();
      const Entry entry = read_entry(reader, in, length, max_bytes);
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
