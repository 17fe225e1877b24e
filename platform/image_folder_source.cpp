#include "platform/image_folder_source.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <system_error>

#include "common/input_error.hpp"
#include "platform/clock.hpp"

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
  decoded_ = cv::imread(files_.front().string(), cv::IMREAD_COLOR);
  if (decoded_.empty()) fail(files_.front().string(), "cannot decode the image (not an image?)");
  info_.width = decoded_.cols;
  info_.height = decoded_.rows;
}

ReadStatus ImageFolderSource::read(cv::Mat& bgr, FrameInfo& info) {
  const auto count = static_cast<std::int64_t>(files_.size());
  if (next_ >= count * loops_) return ReadStatus::end_of_stream;
  const auto& path = files_[static_cast<std::size_t>(next_ % count)];
  // imread has no variant that decodes into an existing buffer; the copy below keeps the
  // caller's buffer (and so the pipeline's slots) stable when the size is unchanged.
  decoded_ = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (decoded_.empty()) {
    last_error_ = path.string() + ": cannot decode the image";
    return ReadStatus::error;
  }
  decoded_.copyTo(bgr);
  ++next_;
  info.frame_number = next_;
  info.pts_ns =
      static_cast<std::int64_t>(std::llround(static_cast<double>(next_ - 1) * 1e9 / fps_));
  info.capture_ns = steady_now_ns();
  return ReadStatus::frame;
}

}  // namespace rtmot::platform
