#pragma once
// An image file's size, read from its header before anything is decoded: a 47 KB PNG can declare
// 20000 x 20000 pixels and cost 2.3 GB once decoded. Written here rather than asked of OpenCV
// because OpenCV's readers offer no header-only call that is public in 4.6 and 4.10 alike
// (ImageDecoder is internal), and its own pixel limit (1 Gpixel) is far above what a frame may be.
#include <optional>
#include <string>
#include <string_view>

namespace rtmot::platform {

/// The largest frame an image may make: each side at most 16384 (as test:// and capture sizes),
/// and at most 8192 x 8192 pixels (192 MB as BGR).
constexpr int kMaxImageSide = 16384;
constexpr long long kMaxImagePixels = 8192LL * 8192LL;

struct ImageSize {
  int width{0};
  int height{0};
};

/// The width and height a PNG, JPEG, BMP or PNM (P1-P6) file declares, from its first bytes;
/// empty when `bytes` is none of those or its header is cut short or malformed.
std::optional<ImageSize> read_image_size(std::string_view bytes);

/// "" when `size` is within the limits above, else why not (for the error message).
std::string check_image_size(ImageSize size);

}  // namespace rtmot::platform
