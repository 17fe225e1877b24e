#include "platform/image_header.hpp"

#include <cctype>
#include <cstdint>

namespace rtmot::platform {
namespace {

std::uint32_t big_endian(std::string_view bytes, std::size_t at, int count) {
  std::uint32_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

std::uint32_t little_endian(std::string_view bytes, std::size_t at, int count) {
  std::uint32_t value = 0;
  for (int i = count - 1; i >= 0; --i)
    value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

std::optional<ImageSize> sized(long long width, long long height) {
  if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX) return std::nullopt;
  return ImageSize{static_cast<int>(width), static_cast<int>(height)};
}

// PNG: the signature, then the IHDR chunk (length, "IHDR", width, height as 32-bit big-endian).
std::optional<ImageSize> png_size(std::string_view bytes) {
  if (bytes.size() < 24 || bytes.substr(12, 4) != "IHDR") return std::nullopt;
  return sized(big_endian(bytes, 16, 4), big_endian(bytes, 20, 4));
}

// JPEG: markers from SOI on; the first start-of-frame (SOF0..SOF15 but DHT C4, JPG C8, DAC CC)
// holds precision, height, width. Every other marker segment carries its length.
std::optional<ImageSize> jpeg_size(std::string_view bytes) {
  std::size_t at = 2;
  while (at + 4 <= bytes.size()) {
    if (static_cast<unsigned char>(bytes[at]) != 0xFF) return std::nullopt;
    const auto marker = static_cast<unsigned char>(bytes[at + 1]);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
      at += 2;  // no length
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // end, or scan data before a frame
    const std::uint32_t length = big_endian(bytes, at + 2, 2);
    if (length < 2) return std::nullopt;
    const bool frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame) {
      if (at + 9 > bytes.size()) return std::nullopt;
      return sized(big_endian(bytes, at + 7, 2), big_endian(bytes, at + 5, 2));
    }
    at += 2 + length;
  }
  return std::nullopt;
}

// BMP: BITMAPINFOHEADER's width and height (signed 32-bit little-endian; a negative height is a
// top-down image); the old BITMAPCOREHEADER (12 bytes) has 16-bit ones.
std::optional<ImageSize> bmp_size(std::string_view bytes) {
  if (bytes.size() < 26) return std::nullopt;
  if (little_endian(bytes, 14, 4) == 12) {
    return sized(little_endian(bytes, 18, 2), little_endian(bytes, 20, 2));
  }
  const auto width = static_cast<std::int32_t>(little_endian(bytes, 18, 4));
  const auto height = static_cast<std::int32_t>(little_endian(bytes, 22, 4));
  return sized(width, height < 0 ? -static_cast<long long>(height) : height);
}

// PNM: "P1".."P6", then width and height as decimal text between whitespace and # comments.
std::optional<ImageSize> pnm_size(std::string_view bytes) {
  std::size_t at = 2;
  long long numbers[2] = {0, 0};
  for (long long& number : numbers) {
    while (at < bytes.size()) {
      if (bytes[at] == '#') {
        while (at < bytes.size() && bytes[at] != '\n') ++at;
      } else if (std::isspace(static_cast<unsigned char>(bytes[at]))) {
        ++at;
      } else {
        break;
      }
    }
    const std::size_t start = at;
    while (at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at])) &&
           at - start < 10) {
      number = number * 10 + (bytes[at] - '0');
      ++at;
    }
    if (at == start || at >= bytes.size()) return std::nullopt;
  }
  return sized(numbers[0], numbers[1]);
}

}  // namespace

std::optional<ImageSize> read_image_size(std::string_view bytes) {
  if (bytes.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8)) return png_size(bytes);
  if (bytes.size() >= 3 && bytes.substr(0, 3) == "\xFF\xD8\xFF") return jpeg_size(bytes);
  if (bytes.substr(0, 2) == "BM") return bmp_size(bytes);
  if (bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6' &&
      std::isspace(static_cast<unsigned char>(bytes[2]))) {
    return pnm_size(bytes);
  }
  return std::nullopt;
}

std::string check_image_size(ImageSize size) {
  const std::string declared = std::to_string(size.width) + "x" + std::to_string(size.height);
  if (size.width > kMaxImageSide || size.height > kMaxImageSide) {
    return "declares " + declared + " pixels, a side longer than " + std::to_string(kMaxImageSide);
  }
  if (static_cast<long long>(size.width) * size.height > kMaxImagePixels) {
    return "declares " + declared + " pixels, more than " + std::to_string(kMaxImagePixels) +
           " (8192x8192)";
  }
  return {};
}

}  // namespace rtmot::platform
