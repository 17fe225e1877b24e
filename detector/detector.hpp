#pragma once
// What the pipeline needs of a detector: boxes for one image, or for a batch of images (one per
// source) in one call. Implementations: the SSD on OpenCV DNN (ssd_detector.hpp) and the replay of
// MOTChallenge detection files (replay_detector.hpp).
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "tracker/box.hpp"

namespace rtmot::detector {

class Detector {
 public:
  virtual ~Detector() = default;

  /// Detects objects in `bgr_image` (8-bit BGR). `frame_number` is the source's 1-based frame
  /// number (the replay detector looks its boxes up by it). Clears `out` and fills it, boxes in
  /// pixels.
  virtual void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
                      std::vector<tracker::Detection>& out) = 0;

  /// Detects objects in `count` images at once: `images[i]` (8-bit BGR, any sizes) with
  /// `frame_numbers[i]` gives `out[i]`, exactly what detect() would give for it. `out` is grown to
  /// `count` entries when it is shorter and never shrunk, so the per-image vectors keep their
  /// capacity when the batch size varies from call to call; entries from `count` on are left
  /// untouched. Any `count` >= 1 is accepted: a detector splits batches larger than max_batch()
  /// itself. The default runs detect() per image; the SSD runs up to max_batch() images in one
  /// forward pass (what makes many cameras on one GPU pay, see docs/gpu.md).
  virtual void detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers,
                            int count, std::vector<std::vector<tracker::Detection>>& out);

  /// The largest batch one pass of the network takes (1 when detect_batch() just loops). A
  /// multi-source pipeline hands over at most this many images per call for the best throughput.
  virtual int max_batch() const { return 1; }

  /// One line for the log: model, backend and why that backend was chosen.
  virtual std::string describe() const = 0;
};

}  // namespace rtmot::detector
