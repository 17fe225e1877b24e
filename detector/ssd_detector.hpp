#pragma once
// The COCO SSDLite-MobileNetV2 (model imported by scripts/fetch_model.sh; see docs/model.md): the
// forward pass on OpenCV DNN (CUDA, FP16 on Jetson boards, when available) or on XNNPACK
// (docs/cpu-detector.md); one pre-processing, one decoder, one NMS for both.
#include <filesystem>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <opencv2/dnn/dnn.hpp>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/detector.hpp"
#include "detector/dnn_backend.hpp"
#include "detector/forward_fault.hpp"
#include "detector/label_table.hpp"
#include "detector/model_description.hpp"
#include "detector/ssd_defaults.hpp"
#include "detector/ssd_postprocess.hpp"
#include "detector/xnnpack_network.hpp"

namespace rtmot::detector {

struct SsdConfig {
  std::filesystem::path model_path{"models/ssdlite_mobilenet_v2_coco.onnx"};
  /// Empty: the model path with ".onnx" replaced by ".anchors.csv", as fetch_model.sh writes it.
  /// Read for layout deltas only (model_description.hpp).
  std::filesystem::path anchors_path;
  float score_threshold{kDefaultScoreThreshold};
  float nms_iou{kDefaultNmsIou};
  int max_detections{kDefaultMaxDetections};
  std::vector<int> classes{default_classes()};  // columns of the model's labels; empty = all
  /// Drop boxes of shapes their class does not have (box_plausibility.hpp; COCO's classes, so
  /// only for a model labelled by COCO's table).
  bool plausible_shapes{true};
  BackendRequest backend{BackendRequest::automatic};
  Fp16Request fp16{Fp16Request::automatic};
  /// Worker threads: OpenCV's (process-wide: cv::setNumThreads; 0 = leave as is) and XNNPACK's
  /// own pool (0 = one per CPU this process may use). `rtmot run` passes the count it decided.
  int threads{0};
  /// The most images one forward pass takes (detect_batch); 1..kMaxBatchLimit. Above 1 the model
  /// must have a batch dimension (scripts/fetch_model.sh exports one since model format 2).
  int max_batch{1};
  /// Check the files listed in the model's .sha256 (written by fetch_model.sh) before loading.
  bool verify_checksums{true};
  /// backend xnnpack-int8: the calibrated activation ranges; empty = the committed file of the
  /// model (default_activation_ranges_path).
  std::filesystem::path int8_ranges;
  /// backend xnnpack (fp32) only: record every tensor's range (`rtmot model calibrate`).
  bool record_ranges{false};
};

/// The largest max_batch accepted: 64 images are 69 MB of input blob, far past where batching
/// stops paying (docs/gpu.md).
constexpr int kMaxBatchLimit = 64;

/// The anchors file that belongs to `model_path` when the config does not name one.
std::filesystem::path default_anchors_path(const std::filesystem::path& model_path);

/// The error of a forward pass that fails once the detector runs (a CUDA graph or stream failure,
/// a lost GPU): names the backend and, on CUDA, the way out (`backend: cpu`); exit code bad_model.
InputError forward_failure(const BackendChoice& backend, const std::string& what);

/// One thread at a time: detect() and detect_batch() work in the detector's own buffers.
class SsdDetector : public Detector {
 public:
  /// Checks the model's checksums (when its .sha256 is there), loads it and runs it once (at
  /// max_batch images when that is above 1). Throws rtmot::InputError: ExitCode::bad_model naming
  /// the file when the model or anchors are missing, unreadable, damaged (checksum), truncated or
  /// corrupt, compute non-finite values, or (max_batch > 1) the model has no batch dimension; on
  /// xnnpack also for an operator it does not build, a wrong input shape or non-finite weights
  /// (backend auto then falls back to OpenCV's CPU path, with a warning saying why);
  /// ExitCode::usage for a backend that cannot be had, class ids outside 1..90 or a max_batch
  /// outside 1..kMaxBatchLimit.
  explicit SsdDetector(SsdConfig config);
  SsdDetector(const SsdDetector&) = delete;  // planes_ point into blob_
  SsdDetector& operator=(const SsdDetector&) = delete;

  void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override;
  /// One forward pass per max_batch() images; no allocation of ours once `out` has its size. Two
  /// networks of fixed input shape do the work: one for single images, one for max_batch images,
  /// which also runs every batch in between, its unused slots computed and ignored, because a
  /// change of input shape makes OpenCV re-plan every layer: measured 140 ms a change on CUDA
  /// (H100), 7-20 ms on the CPU, against a few ms for the padding (docs/gpu.md).
  void detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers, int count,
                    std::vector<std::vector<tracker::Detection>>& out) override;
  int max_batch() const override { return config_.max_batch; }
  /// Wall time of the last forward pass alone (setInput + forward; on CUDA it includes the upload
  /// and the download of the outputs, which OpenCV does synchronously; on XNNPACK the run and the
  /// joining of the output heads), for benchmarks and stats.
  std::int64_t last_forward_ns() const { return last_forward_ns_; }
  /// Wall time of the last detect()/detect_batch() call's preprocessing (resize, normalise, into
  /// the input blob) of all its images, for benchmarks.
  std::int64_t last_preprocess_ns() const { return last_preprocess_ns_; }
  std::string describe() const override;
  /// How the model is fed and read (its .model.yaml, or the bundled contract), and its labels.
  const ModelDescription& description() const { return description_; }
  const LabelTable& labels() const { return labels_; }

  const BackendChoice& backend() const { return backend_; }
  /// On XNNPACK with a pool: how its passes ran (pool or caller's thread), for benchmarks.
  std::string xnnpack_pool_use() const { return xnn_ ? xnn_->pool_use() : std::string(); }
  /// With record_ranges: each tensor's range over the detections since the last clear.
  ActivationRanges recorded_ranges() const {
    return xnn_ ? xnn_->recorded_ranges() : ActivationRanges{};
  }
  void clear_recorded_ranges() {
    if (xnn_) xnn_->clear_recorded_ranges();
  }

 private:
  /// Layout deltas: decoded against the anchors file; decoded: sized at the first pass.
  SsdPostprocessor make_postprocessor() const;
  void preprocess(const cv::Mat& bgr_image, int slot);
  /// preprocess() of images[0..count) into slots 0..count, the images in parallel (OpenCV's
  /// thread pool), timed into last_preprocess_ns_.
  void preprocess_batch(const cv::Mat* const* images, int count);
  /// Runs a network on the first `count` images of blob_ (count <= max_batch): net_ for one,
  /// batch_net_ on all max_batch slots otherwise.
  void forward(int count);
  void warm_up(int count);
  /// The XNNPACK network; null (backend_ switched to OpenCV's CPU path, with the reason) when
  /// backend auto chose it and the model cannot be built there.
  std::unique_ptr<XnnpackNetwork> build_xnnpack();
  /// Its start-up passes; false (and the same switch) when auto chose it and they fail.
  bool start_xnnpack();
  void start_opencv();
  /// Backend auto on the CPU (BackendChoice::measure): with XNNPACK started, starts OpenCV too,
  /// times kMeasuredPasses forward passes of each in turn, keeps the engine of the lower median
  /// and says so in backend_.reason (the start-up log's line).
  void keep_the_faster_engine();
  static constexpr int kMeasuredPasses = 5;
  void fall_back_to_opencv(const std::string& why);

  SsdConfig config_;
  ModelDescription description_;
  LabelTable labels_;
  BackendChoice backend_;
  // The model is loaded before the anchors are read (a damaged model is named first).
  std::unique_ptr<XnnpackNetwork> xnn_;  // when backend_.engine is xnnpack
  cv::dnn::Net net_;                     // input 1 x 3 x size x size, always
  cv::dnn::Net batch_net_;               // input max_batch x 3 x size x size, when max_batch > 1
  SsdPostprocessor postprocess_;
  // Reused every frame (sizes fixed by the network), so steady state allocates no image buffers;
  // one of each per batch slot, so that a batch's images are preprocessed in parallel.
  std::vector<cv::Mat> resized_;     // size x size BGR, 8-bit
  std::vector<cv::Mat> normalized_;  // size x size BGR, float, as the description says
  cv::Mat blob_;                     // max_batch x 3 x size x size planes: the network input
  // 4-D headers on blob_'s first image and on all of it, made once because a 4-D cv::Mat header
  // allocates its size/step arrays.
  cv::Mat single_view_;
  cv::Mat batch_view_;
  std::vector<cv::Mat> planes_;  // headers on blob_'s planes, 3 per image, in BGR order for split

  std::vector<cv::Mat> outputs_;
  std::vector<cv::String> output_names_;
  std::vector<cv::Mat> xnn_inputs_;  // size x size float headers on xnn_'s input, per image
  // The last pass's outputs, [images, anchors, 4] and [images, anchors, columns], either engine.
  const float* boxes_{nullptr};
  const float* logits_{nullptr};
  std::int64_t last_forward_ns_{0};
  std::int64_t last_preprocess_ns_{0};
  bool running_{false};  // start-up (warm-up) is over
  ForwardFault fault_;   // the test hook RTMOT_FAULT_FORWARD_AFTER (detector/forward_fault.hpp)
};

}  // namespace rtmot::detector
