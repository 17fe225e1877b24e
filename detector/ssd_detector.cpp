#include "detector/ssd_detector.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "detector/coco_labels.hpp"

namespace rtmot::detector {
namespace {

constexpr int kInputSize = 300;                   // the network's fixed input, square
constexpr int kNumClasses = kCocoMaxClassId + 1;  // with the background column
constexpr double kPixelScale = 1.0 / 127.5;  // [0, 255] -> [-1, 1], as the graph's Preprocessor

InputError model_error(const std::filesystem::path& path, const std::string& problem) {
  return InputError(path.string(), 0, "", problem, ExitCode::bad_model);
}

cv::dnn::Net load_network(const std::filesystem::path& path, const BackendChoice& backend) {
  if (!std::filesystem::is_regular_file(path)) {
    throw model_error(path, "model file not found (run scripts/fetch_model.sh)");
  }
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(path.string());
  } catch (const cv::Exception& e) {
    throw model_error(path,
                      "cannot load the model (truncated or corrupt? run "
                      "scripts/fetch_model.sh again): " +
                          e.msg);
  }
  if (net.empty()) throw model_error(path, "the model holds no network");
  net.setPreferableBackend(backend.backend);
  net.setPreferableTarget(backend.target);
  return net;
}

SsdPostprocessConfig postprocess_config(const SsdConfig& config) {
  for (const int id : config.classes) {
    if (id < 1 || id > kCocoMaxClassId) {
      throw InputError("", 0, "classes",
                       "COCO class id " + std::to_string(id) + " is outside 1..90",
                       ExitCode::usage);
    }
  }
  return {config.score_threshold, config.nms_iou, config.max_detections, config.classes};
}

std::filesystem::path anchors_path_of(const SsdConfig& config) {
  return config.anchors_path.empty() ? default_anchors_path(config.model_path)
                                     : config.anchors_path;
}

}  // namespace

std::filesystem::path default_anchors_path(const std::filesystem::path& model_path) {
  std::filesystem::path path = model_path;
  return path.replace_extension(".anchors.csv");
}

SsdDetector::SsdDetector(SsdConfig config)
    : config_(std::move(config)),
      backend_(choose_backend(config_.backend, config_.fp16, probe_backend_capabilities())),
      net_(load_network(config_.model_path, backend_)),
      postprocess_(read_anchors(anchors_path_of(config_)), kNumClasses,
                   postprocess_config(config_)),
      resized_(kInputSize, kInputSize, CV_8UC3),
      normalized_(kInputSize, kInputSize, CV_32FC3),
      output_names_{"box_encodings", "class_logits"} {
  if (config_.threads > 0) cv::setNumThreads(config_.threads);
  const int blob_shape[] = {1, 3, kInputSize, kInputSize};
  blob_.create(4, blob_shape, CV_32F);
  blob_.setTo(0.F);
  // cv::split writes channel k (BGR order) into planes_[k]; they point at the RGB planes 2, 1, 0.
  for (int bgr = 0; bgr < 3; ++bgr) {
    planes_.emplace_back(kInputSize, kInputSize, CV_32F, blob_.ptr<float>(0, 2 - bgr));
  }
  // One forward pass now: it checks the model against its anchors and moves the one-off costs
  // (layer allocation, CUDA context) out of the first frame.
  try {
    net_.setInput(blob_);
    net_.forward(outputs_, output_names_);
  } catch (const cv::Exception& e) {
    throw model_error(config_.model_path, "the model does not run: " + e.msg);
  }
  const auto anchors = static_cast<std::size_t>(postprocess_.num_anchors());
  if (outputs_.size() != 2 || outputs_[0].total() != anchors * 4 ||
      outputs_[1].total() != anchors * kNumClasses) {
    throw model_error(config_.model_path,
                      "the model's outputs do not match " + std::to_string(anchors) +
                          " anchors x (4 box codes, 91 classes): wrong model or anchors file");
  }
  // The choice and its reason are logged by whoever builds the pipeline (describe()), once.
}

void SsdDetector::preprocess(const cv::Mat& bgr_image) {
  // Bilinear with half-pixel centres (cv::resize), as the reference detections were made (see
  // docs/model.md). The TF graph's own ResizeBilinear (no half-pixel centres) samples up to 0.8
  // source pixels elsewhere; measured on vtest.avi that moves scores by up to 0.17 against the
  // reference, this way by 5e-5.
  cv::resize(bgr_image, resized_, resized_.size(), 0.0, 0.0, cv::INTER_LINEAR);
  resized_.convertTo(normalized_, CV_32F, kPixelScale, -1.0);
  cv::split(normalized_, planes_.data());  // into blob_, reordered to RGB
}

void SsdDetector::detect(const cv::Mat& bgr_image, std::int64_t /*frame_number*/,
                         std::vector<tracker::Detection>& out) {
  if (bgr_image.empty() || bgr_image.type() != CV_8UC3) {
    throw std::invalid_argument("SsdDetector::detect: expects a non-empty 8-bit BGR image");
  }
  preprocess(bgr_image);
  net_.setInput(blob_);
  // What OpenCV still allocates per frame (measured, OpenCV 4.6, CPU, 1 thread): forward() makes
  // about 1000 small heap allocations (per-layer bookkeeping: Mat vectors, scratch of at most
  // 64 KB) and returns headers on the network's own output blobs; cv::resize two interpolation
  // tables (14 KB). No buffer the size of an image or blob: those above are reused.
  net_.forward(outputs_, output_names_);
  postprocess_.run(outputs_[0].ptr<float>(), outputs_[1].ptr<float>(), bgr_image.cols,
                   bgr_image.rows, out);
}

std::string SsdDetector::describe() const {
  std::ostringstream text;
  text << "SSDLite-MobileNetV2 COCO (" << config_.model_path.string() << ") on " << backend_.name
       << " (" << backend_.reason << "), score >= " << config_.score_threshold << ", NMS IoU "
       << config_.nms_iou << ", classes ";
  if (config_.classes.empty()) text << "all";
  for (std::size_t i = 0; i < config_.classes.size(); ++i) {
    const int id = config_.classes[i];
    text << (i ? "," : "") << id << " (" << coco_label(id) << ")";
  }
  return text.str();
}

}  // namespace rtmot::detector
