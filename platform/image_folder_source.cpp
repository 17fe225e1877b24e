#include "platform/image_folder_source.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <system_error>

#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "platform/clock.hpp"
#include "platform/image_header.hpp"

namespace rtmot::platform {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& problem) {
  throw InputError(where, 0, "", problem, ExitCode::source_failed);
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// Natural order: runs of digits compare as numbers, so frame2 < frame10 (names without numbers,
// and zero-padded ones, keep their plain order). Ties (e.g. "01" vs "1") fall back to the bytes.
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() && j < b.size()) {
    const bool digit_a = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool digit_b = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (digit_a && digit_b) {
      std::size_t end_a = i;
      std::size_t end_b = j;
      while (end_a < a.size() && std::isdigit(static_cast<unsigned char>(a[end_a]))) ++end_a;
      while (end_b < b.size() && std::isdigit(static_cast<unsigned char>(b[end_b]))) ++end_b;
      std::size_t start_a = i;
      std::size_t start_b = j;
      while (start_a + 1 < end_a && a[start_a] == '0') ++start_a;
      while (start_b + 1 < end_b && b[start_b] == '0') ++start_b;
      const std::size_t len_a = end_a - start_a;
      const std::size_t len_b = end_b - start_b;
      if (len_a != len_b) return len_a < len_b;
      const int order = a.compare(start_a, len_a, b, start_b, len_b);
      if (order != 0) return order < 0;
      i = end_a;
      j = end_b;
      continue;
    }
    if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
    ++i;
    ++j;
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return a < b;
}

// The largest image file read: an uncompressed 8192x8192 BMP is 192 MB.
constexpr std::uint64_t kMaxImageFileBytes = 256ULL << 20;

// Reads `path` whole into `bytes` (through the one input reader: regular files only, bounded, read
// errors reported) and decodes it once its header declared a frame within the limits. Throws
// InputError naming the file.
void read_image(const std::filesystem::path& path, std::string& bytes, cv::Mat& decoded) {
  InputFile file(path, kMaxImageFileBytes);
  bytes.resize(static_cast<std::size_t>(file.size()));
  bytes.resize(file.read(bytes.data(), bytes.size()));
  const auto size = read_image_size(bytes);
  if (!size) {
    throw InputError(path.string(), 0, "", "not a PNG, JPEG, BMP or PNM image (unknown header)");
  }
  if (const std::string problem = check_image_size(*size); !problem.empty()) {
    throw InputError(path.string(), 0, "", problem);
  }
  const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8UC1, bytes.data());
  decoded = cv::imdecode(encoded, cv::IMREAD_COLOR);
  if (decoded.empty()) throw InputError(path.string(), 0, "", "cannot decode the image");
}

}  // namespace

const std::vector<std::string>& image_folder_extensions() {
  static const std::vector<std::string> extensions{".jpg", ".jpeg", ".png", ".bmp",
                                                   ".ppm", ".pgm",  ".pnm"};
  return extensions;
}

std::vector<std::filesystem::path> list_image_files(const std::filesystem::path& folder,
                                                    const std::string& uri) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    fail(uri, "'" + folder.string() + "' is not a folder" +
                  (error ? " (" + error.message() + ")" : std::string()));
  }
  std::vector<std::filesystem::path> files;
  std::filesystem::directory_iterator it(folder, error);
  if (error) fail(uri, "cannot list '" + folder.string() + "': " + error.message());
  const auto& extensions = image_folder_extensions();
  for (; it != std::filesystem::directory_iterator(); it.increment(error)) {
    if (error) fail(uri, "cannot list '" + folder.string() + "': " + error.message());
    const auto& path = it->path();
    const std::string extension = lowercase(path.extension().string());
    if (std::find(extensions.begin(), extensions.end(), extension) == extensions.end()) continue;
    if (!it->is_regular_file(error)) continue;
    files.push_back(path);
  }
  if (files.empty()) {
    fail(uri,
         "no image files (.jpg, .jpeg, .png, .bmp, .ppm, .pgm, .pnm) in '" + folder.string() + "'");
  }
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return files;
}

ImageFolderSource::ImageFolderSource(const VideoUri& uri)
    : files_(list_image_files(uri.location, uri.text)),
      loops_(uri.images.loop),
      fps_(uri.images.fps) {
  info_.uri = uri.text;
  info_.live = false;
  info_.fps = fps_;
  try {
    read_image(files_.front(), file_bytes_, decoded_);
  } catch (const InputError& error) {
    throw InputError("", 0, "", error.what(), ExitCode::source_failed);  // names the file
  }
  info_.width = decoded_.cols;
  info_.height = decoded_.rows;
}

ReadStatus ImageFolderSource::read(cv::Mat& bgr, FrameInfo& info) {
  const auto count = static_cast<std::int64_t>(files_.size());
  if (next_ >= count * loops_) return ReadStatus::end_of_stream;
  const auto& path = files_[static_cast<std::size_t>(next_ % count)];
  // imdecode has no variant that decodes into an existing buffer; the copy below keeps the
  // caller's buffer (and so the pipeline's slots) stable when the size is unchanged.
  try {
    read_image(path, file_bytes_, decoded_);
  } catch (const InputError& error) {
    last_error_ = error.what();
    return ReadStatus::error;
  }
  decoded_.copyTo(bgr);
  ++next_;
  info.frame_number = next_;
  info.pts_ns = frame_time_ns(next_ - 1, fps_);
  info.capture_ns = steady_now_ns();
  return ReadStatus::frame;
}

}  // namespace rtmot::platform
