#pragma once
// A folder of image files as a video source: images://DIR[?fps=N&loop=K], or a plain path to a
// folder. Files are played in natural order of their names (frame2.png before frame10.png; MOT
// sequences' 000001.jpg ... sort the same either way), one frame per file, pts = (n - 1) / fps.
// It needs no GStreamer, so machines without it (the GPU test machine) can run the pipeline, and
// MOTChallenge sequences (img1/) play directly. Not live: every frame is delivered.
#include <filesystem>
#include <string>
#include <vector>

#include "platform/video_source.hpp"
#include "platform/video_uri.hpp"

namespace rtmot::platform {

/// The image file extensions the source plays (lower case): what OpenCV's imgcodecs reads in
/// every build rtmot uses (scripts/build_opencv.sh keeps JPEG when libjpeg is there, and PNG).
const std::vector<std::string>& image_folder_extensions();

/// The image files of `folder` in play order; throws InputError(source_failed) naming `uri` when
/// the folder cannot be listed or holds no image file.
std::vector<std::filesystem::path> list_image_files(const std::filesystem::path& folder,
                                                    const std::string& uri);

class ImageFolderSource final : public VideoSource {
 public:
  /// Lists the folder and decodes the first image (so that info() has its size and a folder of
  /// undecodable files fails here): throws InputError(source_failed) naming the URI or the file.
  explicit ImageFolderSource(const VideoUri& uri);

  /// Decodes the next file into `bgr` (8-bit BGR; grey and 16-bit images are converted). A file
  /// that cannot be read or decoded, or whose header declares more pixels than a frame may have
  /// (image_header.hpp: checked before decoding), is an `error` naming it (last_error()); after
  /// the last file (of the last loop) `end_of_stream`.
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override;
  const SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return last_error_; }

  std::size_t file_count() const { return files_.size(); }

 private:
  std::vector<std::filesystem::path> files_;
  int loops_;
  double fps_;
  SourceInfo info_;
  std::string last_error_;
  std::int64_t next_{0};    // index of the next frame over all loops
  std::string file_bytes_;  // the encoded file, reused: read through InputFile, header checked
  cv::Mat decoded_;
};

}  // namespace rtmot::platform
