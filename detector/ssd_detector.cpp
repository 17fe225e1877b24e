#include "detector/ssd_detector.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "detector/model_checksum.hpp"
#include "detector/model_contract.hpp"
#include "detector/model_files.hpp"

namespace rtmot::detector {
namespace {

InputError model_error(const std::filesystem::path& path, const std::string& problem) {
  return InputError(path.string(), 0, "", problem, ExitCode::bad_model);
}

// A model path that cannot even be looked at (a folder without permission, a name too long) is the
// user's problem to fix, like a missing file: say which, with the model's exit code.
void require_readable_file(const std::filesystem::path& path, const char* what) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error && error != std::errc::no_such_file_or_directory &&
      error != std::errc::not_a_directory) {
    throw model_error(path, std::string("cannot access the ") + what + ": " + error.message());
  }
  if (std::filesystem::is_directory(status)) {
    throw model_error(path, std::string("the ") + what + " path is a folder, not a file");
  }
  if (!std::filesystem::exists(status)) {
    throw model_error(path, std::string(what) + " file not found (run scripts/fetch_model.sh)");
  }
  // Opened (and closed) as every input is: a FIFO or device named here never reaches OpenCV's
  // own reader, which would block on it or read it without end.
  open_model_file(path, kMaxModelBytes, what);
}

// OpenCV's own message, on one line: e.msg spans lines (OpenCV's version, source file and line,
// then the text); e.err is the text, which may itself hold line breaks.
std::string one_line(const cv::Exception& e) {
  std::string text;
  for (const char c : e.err) {
    if (c == '\n' || c == '\r') {
      if (!text.empty() && text.back() != ' ') text += "; ";
    } else {
      text += c;
    }
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == ';')) text.pop_back();
  return text;
}

// A model whose declared sizes ask for more memory than there is is a bad model, not an internal
// error: the one message for both engines' start-up.
InputError out_of_memory(const std::filesystem::path& path) {
  return model_error(path,
                     "the model asks for more memory than this machine gives (declared sizes "
                     "too large: damaged model? run scripts/fetch_model.sh again)");
}

cv::dnn::Net load_network(const std::filesystem::path& path, const BackendChoice& backend) {
  require_readable_file(path, "model");
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(path.string());
  } catch (const cv::Exception& e) {
    throw model_error(path,
                      "cannot load the model (truncated or corrupt? run "
                      "scripts/fetch_model.sh again): " +
                          one_line(e));
  } catch (const std::bad_alloc&) {
    throw out_of_memory(path);
  }
  if (net.empty()) throw model_error(path, "the model holds no network");
  net.setPreferableBackend(backend.backend);
  net.setPreferableTarget(backend.target);
  return net;
}

// The shape limits (box_plausibility.hpp) are COCO's classes': a model of other labels gets none.
SsdPostprocessConfig postprocess_config(const SsdConfig& config,
                                        const ModelDescription& description,
                                        const LabelTable& labels) {
  for (const int id : config.classes) {
    if (id < 1 || id >= labels.columns()) {
      throw InputError("", 0, "classes",
                       "class id " + std::to_string(id) + " is outside 1.." +
                           std::to_string(labels.columns() - 1) + " (labels: " + labels.source() +
                           ")",
                       ExitCode::usage);
    }
  }
  return {config.score_threshold, config.nms_iou, config.max_detections, config.classes,
          config.plausible_shapes && description.labels.empty()};
}

LabelTable labels_of(const ModelDescription& description) {
  return description.labels.empty() ? LabelTable::coco()
                                    : LabelTable::from_file(description.labels);
}

std::filesystem::path anchors_path_of(const SsdConfig& config) {
  return config.anchors_path.empty() ? default_anchors_path(config.model_path)
                                     : config.anchors_path;
}

// Runs before anything is loaded, so a damaged download is named as such rather than surfacing as
// a parse error or, worse, as plausible but wrong boxes.
BackendChoice checked_backend(const SsdConfig& config) {
  if (config.max_batch < 1 || config.max_batch > kMaxBatchLimit) {
    throw InputError(
        "", 0, "max_batch",
        std::to_string(config.max_batch) + " is outside 1.." + std::to_string(kMaxBatchLimit),
        ExitCode::usage);
  }
  BackendChoice choice = choose_backend(config.backend, config.fp16, probe_backend_capabilities());
  if (config.verify_checksums) {
    require_readable_file(config.model_path, "model");
    verify_model_checksums(checksum_path_of(config.model_path), config.model_path,
                           anchors_path_of(config));
  }
  return choice;
}

}  // namespace

InputError forward_failure(const BackendChoice& backend, const std::string& what) {
  const bool gpu = backend.backend == cv::dnn::DNN_BACKEND_CUDA;
  return InputError("", 0, "",
                    "detector: the forward pass failed on " + backend.name + " at run time (" +
                        what + ")" +
                        (gpu ? ": set 'backend: cpu' in the detector config to run without the GPU"
                             : ": run scripts/fetch_model.sh again, or try another backend"),
                    ExitCode::bad_model);
}

std::filesystem::path default_anchors_path(const std::filesystem::path& model_path) {
  std::filesystem::path path = model_path;
  return path.replace_extension(".anchors.csv");
}

SsdDetector::SsdDetector(SsdConfig config)
    : config_(std::move(config)),
      description_(read_model_description(config_.model_path)),
      labels_(labels_of(description_)),
      backend_(checked_backend(config_)),
      xnn_(backend_.engine == Engine::xnnpack ? build_xnnpack() : nullptr),
      net_(backend_.engine == Engine::opencv ? load_network(config_.model_path, backend_)
                                             : cv::dnn::Net()),
      postprocess_(make_postprocessor()),
      output_names_{description_.box_output, description_.score_output} {
  if (config_.threads > 0) cv::setNumThreads(config_.threads);
  const int size = description_.input_size;
  for (int slot = 0; slot < config_.max_batch; ++slot) {
    resized_.emplace_back(size, size, CV_8UC3);
    normalized_.emplace_back(size, size, CV_32FC3);
  }
  if (backend_.engine != Engine::xnnpack || !start_xnnpack()) {
    start_opencv();
  } else if (backend_.measure) {
    keep_the_faster_engine();
  }
  running_ = true;
  // The choice and its reason are logged by whoever builds the pipeline (describe()), once.
}

SsdPostprocessor SsdDetector::make_postprocessor() const {
  const SsdPostprocessConfig postprocess = postprocess_config(config_, description_, labels_);
  if (description_.layout == OutputLayout::decoded) {
    return SsdPostprocessor::decoded(labels_.columns(), postprocess);
  }
  return SsdPostprocessor(read_anchors(anchors_path_of(config_)), labels_.columns(), postprocess);
}

std::unique_ptr<XnnpackNetwork> SsdDetector::build_xnnpack() {
  try {
    XnnpackNetworkConfig xnn;
    xnn.model_path = config_.model_path;
    xnn.input_size = description_.input_size;
    xnn.box_output = description_.box_output;
    xnn.logit_output = description_.score_output;
    xnn.max_batch = config_.max_batch;
    xnn.threads = config_.threads;
    if (backend_.int8) {
      xnn.int8_ranges = config_.int8_ranges.empty()
                            ? default_activation_ranges_path(config_.model_path)
                            : config_.int8_ranges;
    }
    xnn.record_ranges = config_.record_ranges;
    try {
      return std::make_unique<XnnpackNetwork>(xnn);
    } catch (const std::bad_alloc&) {
      throw out_of_memory(config_.model_path);
    }
  } catch (const InputError& e) {
    if (config_.backend != BackendRequest::automatic || e.exit_code() != ExitCode::bad_model) {
      throw;
    }
    fall_back_to_opencv(e.what());
    return nullptr;
  }
}

bool SsdDetector::start_xnnpack() {
  try {
    for (int image = 0; image < config_.max_batch; ++image) {
      xnn_inputs_.emplace_back(description_.input_size, description_.input_size, CV_32FC3,
                               xnn_->input(image));
    }
    warm_up(1);
    if (config_.max_batch > 1) warm_up(config_.max_batch);
    return true;
  } catch (const InputError& e) {
    if (config_.backend != BackendRequest::automatic || e.exit_code() != ExitCode::bad_model) {
      throw;
    }
    fall_back_to_opencv(e.what());
    xnn_.reset();
    xnn_inputs_.clear();
    return false;
  }
}

// auto: the model may still run on OpenCV (an operator XNNPACK lacks); if not, OpenCV's own
// start-up says why.
void SsdDetector::fall_back_to_opencv(const std::string& why) {
  spdlog::warn("detector: xnnpack cannot run the model ({}); falling back to OpenCV's cpu backend",
               why);
  backend_ = {Engine::opencv, cv::dnn::DNN_BACKEND_OPENCV, cv::dnn::DNN_TARGET_CPU, "cpu",
              "xnnpack cannot run the model (" + why + ")"};
}

// Both engines are started (loaded, warmed up) and timed in turn, pass by pass, on the start-up
// input, so that a load that comes and goes hits both alike; the slower is released.
void SsdDetector::keep_the_faster_engine() {
  std::unique_ptr<XnnpackNetwork> xnn = std::move(xnn_);  // start_opencv() runs without it
  std::vector<cv::Mat> xnn_inputs = std::move(xnn_inputs_);
  start_opencv();
  std::vector<double> xnn_ms;
  std::vector<double> opencv_ms;
  for (int pass = 0; pass < kMeasuredPasses; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    xnn->run(1);
    xnn_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    forward(1);
    opencv_ms.push_back(static_cast<double>(last_forward_ns_) * 1e-6);
  }
  const auto median = [](std::vector<double> ms) {
    std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
    return ms[ms.size() / 2];
  };
  const double xnn_median = median(xnn_ms);
  const double opencv_median = median(opencv_ms);
  const bool xnnpack = xnn_median <= opencv_median;
  std::ostringstream why;
  why.precision(3);
  why << backend_.reason.substr(0, backend_.reason.find(';')) << "; measured at start on "
      << (config_.threads > 0 ? std::to_string(config_.threads) + " thread(s)"
                              : std::string("one thread per CPU"))
      << ", forward median of " << kMeasuredPasses << " passes each: xnnpack " << xnn_median
      << " ms, OpenCV cpu " << opencv_median << " ms: " << (xnnpack ? "xnnpack" : "OpenCV cpu")
      << " is faster here";
  if (xnnpack) {
    backend_ = {Engine::xnnpack, 0, 0, "xnnpack", why.str()};
    xnn_ = std::move(xnn);
    xnn_inputs_ = std::move(xnn_inputs);
    net_ = cv::dnn::Net();
    batch_net_ = cv::dnn::Net();
    outputs_.clear();
    planes_.clear();
    single_view_.release();
    batch_view_.release();
    blob_.release();
    boxes_ = xnn_->boxes();
    logits_ = xnn_->logits();
  } else {
    backend_ = {Engine::opencv, cv::dnn::DNN_BACKEND_OPENCV, cv::dnn::DNN_TARGET_CPU, "cpu",
                why.str()};
  }
}

void SsdDetector::start_opencv() {
  if (net_.empty()) net_ = load_network(config_.model_path, backend_);
  const int batch = config_.max_batch;
  const int size = description_.input_size;
  const int blob_shape[] = {batch, 3, size, size};
  blob_.create(4, blob_shape, CV_32F);
  blob_.setTo(0.F);
  const int single_shape[] = {1, 3, size, size};
  single_view_ = cv::Mat(4, single_shape, CV_32F, blob_.data);
  batch_view_ = blob_;
  if (batch > 1) batch_net_ = load_network(config_.model_path, backend_);
  // cv::split writes channel k (BGR order) into planes_[3 * image + k]; they point at the RGB
  // planes 2, 1, 0 of that image (or planes 0, 1, 2 for a model that takes BGR).
  const bool rgb = description_.colour == ColourOrder::rgb;
  for (int image = 0; image < batch; ++image) {
    for (int bgr = 0; bgr < 3; ++bgr) {
      planes_.emplace_back(size, size, CV_32F, blob_.ptr<float>(image, rgb ? 2 - bgr : bgr));
    }
  }
  // One forward pass now (at the largest batch, which also sizes OpenCV's buffers for it): it
  // checks the model against its anchors and moves the one-off costs (layer allocation, CUDA
  // context, cuDNN plans) out of the first frame.
  warm_up(1);
  if (batch > 1) warm_up(batch);
  if (backend_.backend == cv::dnn::DNN_BACKEND_CUDA) {
    // Our OpenCV captures a network's forward as a CUDA graph on its second run
    // (scripts/opencv/cuda_graph.patch): do it here, so that it never happens on a frame, nor
    // while another detector of this process (a lane of the detect stage: they are built one
    // after another) runs its own.
    warm_up(1);
    if (batch > 1) warm_up(batch);
  }
}

void SsdDetector::warm_up(int count) {
  try {
    forward(count);
  } catch (const cv::Exception& e) {
    throw model_error(config_.model_path, "the model does not run: " + one_line(e));
  } catch (const std::bad_alloc&) {
    throw out_of_memory(config_.model_path);
  } catch (const InputError&) {
    throw;  // already says what and where (a CUDA failure at run time)
  } catch (const std::runtime_error& e) {  // XNNPACK's
    throw model_error(config_.model_path, std::string("the model does not run: ") + e.what());
  }
  const int pass = count == 1 ? 1 : config_.max_batch;  // images the network computed
  const auto images = static_cast<std::size_t>(pass);
  const auto columns = static_cast<std::size_t>(labels_.columns());
  if (description_.layout == OutputLayout::decoded && postprocess_.num_anchors() == 0) {
    // The rows per image are the model's own: read from its first pass's box output.
    const std::size_t rows =
        xnn_ ? xnn_->anchors() : (outputs_.empty() ? 0 : outputs_[0].total() / (images * 4));
    postprocess_.size_for(static_cast<int>(rows));
  }
  const auto anchors = static_cast<std::size_t>(postprocess_.num_anchors());
  const std::string mismatch =
      "the model's outputs do not match " + std::to_string(anchors) + " rows x (4 box values, " +
      std::to_string(columns) + " class columns of " + labels_.source() +
      "): wrong model, anchors or labels file (rtmot model check says which)";
  if (xnn_) {
    if (xnn_->anchors() != anchors || xnn_->classes() != columns) {
      throw model_error(config_.model_path, mismatch);
    }
  } else if (anchors == 0 || outputs_.size() != 2 || outputs_[0].total() != images * anchors * 4 ||
             outputs_[1].total() != images * anchors * columns) {
    throw model_error(config_.model_path, mismatch);
  }
  // A model exported for one image per pass concatenates a batch's anchors into one row (the
  // xnnpack builder refuses such a model's input shape itself).
  if (!xnn_ &&
      (outputs_[0].dims < 3 || outputs_[0].size[0] != pass || outputs_[1].size[0] != pass)) {
    throw model_error(config_.model_path,
                      "the model takes one image per pass (exported before batching), max_batch " +
                          std::to_string(pass) +
                          " needs a batch dimension: run "
                          "scripts/fetch_model.sh again");
  }
  // NaN or infinite weights (a damaged or badly converted model) make every score NaN, and NaN
  // compares false with the threshold: the detector would silently find nothing.
  const auto finite = [](const float* data, std::size_t n) {
    return std::all_of(data, data + n, [](float v) { return std::isfinite(v); });
  };
  if (!finite(boxes_, images * anchors * 4) || !finite(logits_, images * anchors * columns)) {
    throw model_error(config_.model_path,
                      "the model computes NaN or infinite values on its start-up pass (damaged "
                      "weights?): run scripts/fetch_model.sh again");
  }
}

void SsdDetector::forward(int count) {
  const auto start = std::chrono::steady_clock::now();
  if (xnn_) {
    xnn_->run(count);
    boxes_ = xnn_->boxes();
    logits_ = xnn_->logits();
    last_forward_ns_ = std::chrono::duration_cast<std::chrono::nanoseconds>(
                           std::chrono::steady_clock::now() - start)
                           .count();
    return;
  }
  // Each network always sees the same input shape: a new shape would make OpenCV re-plan (and
  // re-allocate) every layer. Slots count.. of a padded batch hold earlier images; their outputs
  // are not read.
  cv::dnn::Net& net = count == 1 ? net_ : batch_net_;
  net.setInput(count == 1 ? single_view_ : batch_view_);
  // What OpenCV still allocates per frame (measured, OpenCV 4.6, CPU, 1 thread): forward() makes
  // about 1000 small heap allocations (per-layer bookkeeping: Mat vectors, scratch of at most
  // 64 KB) and returns headers on the network's own output blobs. No buffer the size of an image
  // or blob: those above are reused.
  try {
    if (running_ && fault_.fails_now()) {
      throw cv::Exception(cv::Error::GpuApiCallError, fault_.what(), "SsdDetector::forward",
                          __FILE__, __LINE__);
    }
    net.forward(outputs_, output_names_);
  } catch (const cv::Exception& e) {
    // At start-up on the CPU, warm_up() says "the model does not run". Otherwise (a replayed
    // graph, a stream, a lost device): name the backend and the way out; exit code bad_model
    // ("does not run"), through the run's usual error path (every output flushed and closed).
    if (!running_ && backend_.backend != cv::dnn::DNN_BACKEND_CUDA) throw;
    // e.err, not e.msg: the failure itself, without OpenCV's file, line and a line break.
    throw forward_failure(backend_, e.err);
  }
  boxes_ = outputs_[0].ptr<float>();
  logits_ = outputs_[1].ptr<float>();
  last_forward_ns_ =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
          .count();
}

namespace {

void require_bgr(const cv::Mat& bgr_image) {
  if (bgr_image.empty() || bgr_image.type() != CV_8UC3) {
    throw std::invalid_argument("SsdDetector: expects non-empty 8-bit BGR images");
  }
}

}  // namespace

void SsdDetector::preprocess(const cv::Mat& bgr_image, int slot) {
  const auto index = static_cast<std::size_t>(slot);
  cv::Mat& resized = resized_[index];
  cv::Mat& normalized = normalized_[index];
  // Bilinear with half-pixel centres (cv::resize), as the reference detections were made (see
  // docs/model.md). The TF graph's own ResizeBilinear (no half-pixel centres) samples up to 0.8
  // source pixels elsewhere; measured on vtest.avi that moves scores by up to 0.17 against the
  // reference, this way by 5e-5. (cv::resize also allocates two small interpolation tables.)
  cv::resize(bgr_image, resized, resized.size(), 0.0, 0.0, cv::INTER_LINEAR);
  resized.convertTo(normalized, CV_32F, description_.scale,
                    -description_.mean * description_.scale);
  if (xnn_) {  // XNNPACK takes NHWC: the same values, interleaved
    if (description_.colour == ColourOrder::rgb) {
      cv::cvtColor(normalized, xnn_inputs_[index], cv::COLOR_BGR2RGB);
    } else {
      normalized.copyTo(xnn_inputs_[index]);
    }
    return;
  }
  cv::split(normalized, planes_.data() + 3 * slot);  // into blob_, reordered to RGB
}

// Why in parallel: on the GPU the lane thread's host work per batch limited the stage, not the
// device (docs/gpu.md §3, "Batches in flight"), and of that host work the preprocessing of the
// batch's images, one after another, is the largest part (measured: docs/gpu.md). Each image
// writes only its own slot's buffers and its own planes of the blob, so the result is the same
// bytes as the serial loop. No option: on one image, or a pool of one thread, parallel_for_ runs
// the body inline; a call from a second lane while the pool is busy runs inline too (OpenCV does
// not nest or share its pool), so it costs nothing where it cannot help.
void SsdDetector::preprocess_batch(const cv::Mat* const* images, int count) {
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i) require_bgr(*images[i]);  // no throw inside the workers
  if (count == 1) {
    preprocess(*images[0], 0);
  } else {
    cv::parallel_for_(cv::Range(0, count), [&](const cv::Range& range) {
      for (int i = range.start; i < range.end; ++i) preprocess(*images[i], i);
    });
  }
  last_preprocess_ns_ =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
          .count();
}

void SsdDetector::detect(const cv::Mat& bgr_image, std::int64_t /*frame_number*/,
                         std::vector<tracker::Detection>& out) {
  const cv::Mat* const image = &bgr_image;
  preprocess_batch(&image, 1);
  forward(1);
  postprocess_.run(boxes_, logits_, bgr_image.cols, bgr_image.rows, out);
}

void SsdDetector::detect_batch(const cv::Mat* const* images, const std::int64_t* /*frame_numbers*/,
                               int count, std::vector<std::vector<tracker::Detection>>& out) {
  if (count < 1) throw std::invalid_argument("SsdDetector::detect_batch: count must be >= 1");
  if (out.size() < static_cast<std::size_t>(count)) out.resize(static_cast<std::size_t>(count));
  const std::size_t box_stride = static_cast<std::size_t>(postprocess_.num_anchors()) * 4;
  const std::size_t logit_stride = static_cast<std::size_t>(postprocess_.num_anchors()) *
                                   static_cast<std::size_t>(labels_.columns());
  for (int first = 0; first < count; first += config_.max_batch) {
    const int n = std::min(config_.max_batch, count - first);
    preprocess_batch(images + first, n);
    forward(n);
    // Outputs are [n, anchors, 4] and [n, anchors, columns]: image i's rows follow image i-1's.
    for (int i = 0; i < n; ++i) {
      const cv::Mat& image = *images[first + i];
      postprocess_.run(boxes_ + static_cast<std::size_t>(i) * box_stride,
                       logits_ + static_cast<std::size_t>(i) * logit_stride, image.cols, image.rows,
                       out[static_cast<std::size_t>(first + i)]);
    }
  }
}

std::string SsdDetector::describe() const {
  std::ostringstream text;
  text << (description_.file.empty() ? "SSDLite-MobileNetV2 COCO (" : "SSD (")
       << config_.model_path.string()
       << (description_.file.empty()
               ? std::string()
               : ", described by " + described_by(description_) + ", layout " +
                     std::string(kOutputLayoutNames.name(description_.layout)))
       << ") on " << backend_.name << " (" << backend_.reason << ")"
       << (xnn_ ? " [" + xnn_->summary() + "]" : std::string())
       << ", batch <= " << config_.max_batch << ", score >= " << config_.score_threshold
       << ", NMS IoU " << config_.nms_iou << ", classes ";
  if (config_.classes.empty()) text << "all";
  for (std::size_t i = 0; i < config_.classes.size(); ++i) {
    const int id = config_.classes[i];
    text << (i ? "," : "") << id << " (" << labels_.name(id) << ")";
  }
  return text.str();
}

}  // namespace rtmot::detector
