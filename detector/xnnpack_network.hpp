#pragma once
// The SSD's forward pass on XNNPACK: the ONNX model the OpenCV backend loads, read with ONNX's own
// protobuf classes (libonnx) and rebuilt as an XNNPACK subgraph (NHWC, weights repacked once);
// what follows the last operator XNNPACK builds (a decoded layout's box decoding and softmax) runs
// on the host after it (xnnpack_decoding_tail.hpp). Only the forward pass: pre- and
// post-processing stay in SsdDetector. See docs/cpu-detector.md.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "detector/activation_ranges.hpp"
#include "detector/model_contract.hpp"

namespace rtmot::detector {

/// True when this build has the XNNPACK backend (libxnnpack-dev and libonnx-dev were found).
bool xnnpack_built();
/// True when XNNPACK also initializes on this processor (it refuses ones it has no kernels for;
/// under emulation its CPU probe may fail too). Where not, building the network is a bad_model
/// error, which backend auto falls back from.
bool xnnpack_runs_here();

/// The ONNX operators the XNNPACK backend builds, for messages and docs.
const char* xnnpack_supported_operators();

struct XnnpackNetworkConfig {
  std::filesystem::path model_path;
  int input_size{kModelInputSize};  // the square input the detector feeds (3 channels)
  int max_batch{1};
  /// Worker threads (pthreadpool); 1 runs on the caller's thread; 0 = one per CPU this process may
  /// use, which also caps a larger count. With a pool, each pass runs on it or on the caller's
  /// thread alone, whichever is faster as measured (detector/pool_governor.hpp).
  int threads{0};
  std::string box_output{kBoxOutputName};
  std::string logit_output{kClassOutputName};
  /// Non-empty: the int8 engine (backend xnnpack-int8). Convolutions and additions run on signed
  /// 8-bit activations (per-tensor scale and zero point from these calibrated ranges) with int8
  /// weights quantized per output channel; the input and the outputs stay fp32 (converted at the
  /// edges). The file must belong to this model (its SHA-256): activation_ranges.hpp.
  std::filesystem::path int8_ranges;
  /// fp32 only: also record every computed tensor's min and max over the runs (calibration,
  /// recorded_ranges()). Slower; for `rtmot model calibrate`, not for detection.
  bool record_ranges{false};
};

/// One thread at a time. Two runtimes of fixed shape share the repacked weights and the thread
/// pool: one for one image, one for max_batch images (as the OpenCV backend, whose reasons hold
/// here too: a shape is planned once, and the steady state allocates nothing).
class XnnpackNetwork {
 public:
  /// Throws rtmot::InputError (ExitCode::bad_model) naming the file: unreadable or corrupt model,
  /// an operator (or attribute) the backend does not build (named, with its node; "op 'X' in the
  /// decoding tail" for one after the network that the host does not run), an input shape
  /// other than N x 3 x input_size x input_size, a fixed batch of 1 with max_batch > 1, non-float
  /// or non-finite weights (naming the tensor), outputs missing.
  explicit XnnpackNetwork(const XnnpackNetworkConfig& config);
  ~XnnpackNetwork();
  XnnpackNetwork(const XnnpackNetwork&) = delete;
  XnnpackNetwork& operator=(const XnnpackNetwork&) = delete;

  /// Image `slot`'s input: input_size x input_size x 3 floats, RGB, interleaved (HWC).
  float* input(int slot);
  /// Runs the first `count` images (1 or up to max_batch; above 1 all max_batch slots are
  /// computed and slots count.. ignored). Allocates nothing.
  void run(int count);
  /// [images, anchors, 4] and [images, anchors, classes] of the last run.
  const float* boxes() const;
  const float* logits() const;
  std::size_t anchors() const;
  std::size_t classes() const;
  /// What was built, for the log: operators and runtimes.
  std::string summary() const;
  /// How the passes so far ran (on the pool or on the caller's thread, and each way's current
  /// estimate), for benchmarks; empty without a pool.
  std::string pool_use() const;
  /// With record_ranges: the range of every tensor (the input's too) over the runs so far, and the
  /// model file's SHA-256 (frames left 0 for the caller).
  ActivationRanges recorded_ranges() const;
  /// Forgets what was recorded (the start-up passes, before the sample frames).
  void clear_recorded_ranges();

 private:
  void record_ranges(int count);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rtmot::detector
