#pragma once
// The COCO SSDLite-MobileNetV2 on OpenCV DNN (model imported by scripts/fetch_model.sh; see
// docs/model.md). CUDA (FP16 on Jetson boards) when available, else the CPU.
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <opencv2/dnn/dnn.hpp>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "detector/dnn_backend.hpp"
#include "detector/ssd_postprocess.hpp"

namespace rtmot::detector {

struct SsdConfig {
  std::filesystem::path model_path{"models/ssdlite_mobilenet_v2_coco.onnx"};
  /// Empty: the model path with ".onnx" replaced by ".anchors.csv", as fetch_model.sh writes it.
  std::filesystem::path anchors_path;
  float score_threshold{0.5F};
  float nms_iou{0.6F};  // the model's own training pipeline value
  int max_detections{100};
  std::vector<int> classes{1};  // COCO ids (1 = person); empty = all
  BackendRequest backend{BackendRequest::automatic};
  Fp16Request fp16{Fp16Request::automatic};
  int threads{0};  // OpenCV's worker threads (process-wide: cv::setNumThreads); 0 = leave as is
};

/// The anchors file that belongs to `model_path` when the config does not name one.
std::filesystem::path default_anchors_path(const std::filesystem::path& model_path);

/// One thread at a time: detect() works in the detector's own buffers.
class SsdDetector : public Detector {
 public:
  /// Loads the model and runs it once. Throws rtmot::InputError: ExitCode::bad_model naming the
  /// file when the model or anchors are missing, truncated or corrupt; ExitCode::usage for a
  /// backend that cannot be had or class ids outside 1..90.
  explicit SsdDetector(SsdConfig config);
  SsdDetector(const SsdDetector&) = delete;  // planes_ point into blob_
  SsdDetector& operator=(const SsdDetector&) = delete;

  void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override;
  std::string describe() const override;

  const BackendChoice& backend() const { return backend_; }

 private:
  void preprocess(const cv::Mat& bgr_image);

  SsdConfig config_;
  BackendChoice backend_;
  cv::dnn::Net net_;
  SsdPostprocessor postprocess_;
  // Reused every frame (sizes fixed by the network), so steady state allocates no image buffers.
  cv::Mat resized_;              // 300x300 BGR, 8-bit
  cv::Mat normalized_;           // 300x300 BGR, float in [-1, 1]
  cv::Mat blob_;                 // 1x3x300x300 RGB planes: the network input
  std::vector<cv::Mat> planes_;  // headers on blob_'s planes, in BGR order for cv::split
  std::vector<cv::Mat> outputs_;
  std::vector<cv::String> output_names_;
};

}  // namespace rtmot::detector
