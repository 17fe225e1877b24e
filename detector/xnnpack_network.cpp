#include "detector/xnnpack_network.hpp"

#include <onnx/onnx_pb.h>
#include <pthreadpool.h>
#include <xnnpack.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <opencv2/core/utility.hpp>
#include <sstream>
#include <vector>

#include "common/input_error.hpp"
#include "detector/model_checksum.hpp"
#include "detector/model_files.hpp"
#include "detector/pool_governor.hpp"
#include "detector/xnnpack_decoding_tail.hpp"
#include "detector/xnnpack_onnx_reading.hpp"
#include "detector/xnnpack_subgraph_builder.hpp"

namespace rtmot::detector {

bool xnnpack_built() {
  return true;
}

bool xnnpack_runs_here() {
  return xnn_initialize(nullptr) == xnn_status_success;
}

const char* xnnpack_supported_operators() {
  return "Conv (any group count, dilation, explicit pads), Clip, Relu, Add (same shapes), "
         "Add, Mul, Sub, Div by a scalar constant, Transpose (NCHW -> NHWC), Reshape, Concat "
         "(axis 1), Identity; after them, on the host, a decoding tail of Slice, Mul, Add, Sub, "
         "Div, Exp, Sigmoid, Softmax, Concat, Reshape, Unsqueeze, Squeeze, Flatten, Identity, "
         "Constant";
}

namespace {

using xnnpack::BuildMode;
using xnnpack::external_outputs;
using xnnpack::kInputExternalId;
using xnnpack::product;
using xnnpack::QuantizedWeights;
using xnnpack::shape_text;
using xnnpack::SubgraphBuilder;
using xnnpack::SubgraphPtr;
using xnnpack::Value;

struct RuntimeDeleter {
  void operator()(xnn_runtime_t runtime) const { xnn_delete_runtime(runtime); }
};
struct PoolDeleter {
  void operator()(pthreadpool_t pool) const { pthreadpool_destroy(pool); }
};
using RuntimePtr = std::unique_ptr<xnn_runtime, RuntimeDeleter>;
using PoolPtr = std::unique_ptr<pthreadpool, PoolDeleter>;

/// An external output's buffer and where its rows go in the joined output.
struct Piece {
  uint32_t id;
  std::size_t per_image;  // floats per image
  std::vector<float> data;
};

/// A tensor the host reads: its pieces joined image by image.
struct JoinedOutput {
  std::string name;
  std::vector<std::size_t> shape;  // ONNX's, for one image (batch 1)
  std::vector<std::size_t> piece_indices;
  std::size_t per_image{0};
  std::size_t width{0};  // the last dimension
  std::vector<float> data;
};

}  // namespace

struct XnnpackNetwork::Impl {
  XnnpackNetworkConfig config;
  onnx::ModelProto model;
  std::map<std::string, std::vector<float>> weights;  // outlive the runtimes (declared first)
  QuantizedWeights quantized_weights;
  ActivationRanges ranges;  // the int8 engine's calibration (empty: fp32)
  std::string model_sha256;
  // Recording ranges: each recorded tensor's external id, its buffer and what it held so far.
  std::map<std::string, uint32_t> probes;
  std::map<uint32_t, std::vector<float>> probe_data;
  std::map<std::string, ActivationRange> recorded;
  PoolPtr pool;
  std::vector<float> input;
  std::vector<Piece> pieces;
  TailSplit split;
  std::vector<JoinedOutput> joined;  // what the host reads, fixed in place before the tails
  // The decoding tail (empty for a model whose outputs XNNPACK computes) per batch size; its
  // outputs 0 and 1 are the boxes and the scores. `last_tail` ran last.
  std::unique_ptr<DecodingTail> single_tail;
  std::unique_ptr<DecodingTail> batched_tail;
  const DecodingTail* last_tail{nullptr};
  // Each batch size twice: on the pool and on the caller's thread alone (no pool), the governor
  // choosing per pass (detector/pool_governor.hpp). Without a pool only the inline ones exist.
  RuntimePtr single_pooled;
  RuntimePtr single_inline;
  RuntimePtr batched_pooled;
  RuntimePtr batched_inline;
  PoolGovernor single_governor;
  PoolGovernor batched_governor;
  std::string summary;
};

XnnpackNetwork::XnnpackNetwork(const XnnpackNetworkConfig& config)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.config = config;
  const auto& path = config.model_path;
  const auto model_error = [&](const std::string& problem) {
    return InputError(path.string(), 0, "", problem, ExitCode::bad_model);
  };
  if (xnn_initialize(nullptr) != xnn_status_success) {
    throw model_error("XNNPACK does not run on this processor");
  }
  std::string bytes;
  try {
    bytes = read_text_file(path, kMaxModelBytes);
  } catch (const InputError& e) {
    throw InputError(e.file(), e.line(), e.field(),
                     std::string("cannot read the model: ") + e.what(),
                     e.exit_code() == ExitCode::bad_input ? ExitCode::bad_model : e.exit_code());
  }
  if (!impl.model.ParseFromString(bytes)) {
    throw model_error("not an ONNX model (truncated or corrupt? run scripts/fetch_model.sh again)");
  }
  const bool int8 = !config.int8_ranges.empty();
  if (int8 && config.record_ranges) {
    throw model_error("ranges are recorded on the fp32 engine, not the int8 one");
  }
  if (int8 || config.record_ranges) impl.model_sha256 = sha256_hex(bytes);
  if (int8) {
    impl.ranges = read_activation_ranges(config.int8_ranges);
    check_ranges_belong_to(impl.ranges, config.int8_ranges, impl.model_sha256);
  }
  bytes = std::string();
  const onnx::GraphProto& graph = impl.model.graph();
  BuildMode mode;
  if (int8) {
    mode.ranges = &impl.ranges;
    mode.ranges_path = &config.int8_ranges;
    mode.quantized = &impl.quantized_weights;
  }
  if (config.record_ranges) mode.probes = &impl.probes;
  for (const auto& output : graph.output()) {
    if (output.name() != config.box_output && output.name() != config.logit_output) {
      throw model_error("the model has outputs other than '" + config.box_output + "' and '" +
                        config.logit_output + "'");
    }
  }
  for (const std::string& name : {config.box_output, config.logit_output}) {
    const auto& outputs = graph.output();
    if (std::none_of(outputs.begin(), outputs.end(),
                     [&](const onnx::ValueInfoProto& o) { return o.name() == name; })) {
      throw model_error("the model has no output '" + name + "'");
    }
  }
  impl.split = split_decoding_tail(path, graph, xnnpack_supported_operators());
  const auto external_ids = external_outputs(graph, impl.split.boundary);

  const auto max_batch = static_cast<std::size_t>(std::max(1, config.max_batch));
  const auto input_size = static_cast<std::size_t>(config.input_size);
  const std::size_t image_floats = input_size * input_size * 3;
  impl.input.assign(max_batch * image_floats + XNN_EXTRA_BYTES / sizeof(float), 0.F);
  // Never more workers than the CPUs this process may use (affinity mask, cpuset, CPU quota: as
  // OpenCV counts them): a pool larger than that spins on every operator for a worker that has no
  // core (measured: 2 threads on one core, 675 ms a forward against 39 ms for OpenCV).
  const int cpus = std::max(1, cv::getNumberOfCPUs());
  const int threads = config.threads > 0 ? std::min(config.threads, cpus) : cpus;
  if (threads > 1) {
    impl.pool.reset(pthreadpool_create(static_cast<std::size_t>(threads)));
    if (!impl.pool) throw model_error("cannot start XNNPACK's thread pool");
  }

  std::map<uint32_t, std::size_t> piece_sizes;  // floats per image of each external output
  const auto make_runtime = [&](std::size_t batch, std::map<std::string, Value>& outputs,
                                pthreadpool_t pool) {
    SubgraphBuilder builder(path, graph, impl.split, impl.weights, external_ids, batch, input_size,
                            mode);
    SubgraphPtr subgraph = builder.build(outputs, piece_sizes);
    xnn_runtime_t raw = nullptr;
    // Workers sleep once a forward is done instead of spinning until the next frame arrives: the
    // pipeline's capture and track threads share these cores between forwards (measured on 2 idle
    // cores: the forward's median and the every-frame FPS unchanged). Between operators they still
    // spin (the flag reaches the last operator only): hence the governor.
    const xnn_status status =
        xnn_create_runtime_v2(subgraph.get(), pool, pool ? XNN_FLAG_YIELD_WORKERS : 0, &raw);
    if (status != xnn_status_success) {
      throw model_error("XNNPACK cannot plan the network (status " +
                        std::to_string(static_cast<int>(status)) + ")");
    }
    return RuntimePtr(raw);
  };

  // Batch 1 first: it names the outputs' pieces and sizes their buffers.
  std::map<std::string, Value> outputs;
  impl.single_inline = make_runtime(1, outputs, nullptr);
  if (impl.pool) impl.single_pooled = make_runtime(1, outputs, impl.pool.get());
  std::map<uint32_t, std::size_t> piece_of;
  for (const std::string& name : impl.split.boundary) {
    JoinedOutput& joined = impl.joined.emplace_back();
    const Value& value = outputs.at(name);
    if (value.shape.size() < 2) throw model_error("the tensor '" + name + "' is not per image");
    joined.name = name;
    joined.shape = value.shape;
    joined.width = value.shape.back();
    joined.per_image = product(value.shape, 1);
    for (const uint32_t id : value.pieces) {
      if (!piece_of.count(id)) {
        piece_of[id] = impl.pieces.size();
        impl.pieces.push_back({id, 0, {}});
      }
      joined.piece_indices.push_back(piece_of[id]);
    }
    joined.data.assign(max_batch * joined.per_image, 0.F);
  }
  if (max_batch > 1) {
    impl.batched_inline = make_runtime(max_batch, outputs, nullptr);
    if (impl.pool) impl.batched_pooled = make_runtime(max_batch, outputs, impl.pool.get());
  }
  for (Piece& piece : impl.pieces) {
    piece.per_image = piece_sizes.at(piece.id);
    piece.data.assign(max_batch * piece.per_image, 0.F);
  }
  for (const JoinedOutput& joined : impl.joined) {
    std::size_t sum = 0;
    for (const std::size_t index : joined.piece_indices) sum += impl.pieces[index].per_image;
    if (sum != joined.per_image) throw model_error("the outputs' pieces do not add up");
  }
  const auto tail_for = [&](std::size_t batch) {
    std::vector<TailInput> inputs;
    for (const JoinedOutput& joined : impl.joined) {
      std::vector<std::size_t> shape = joined.shape;
      shape[0] = batch;
      inputs.push_back({joined.name, shape, joined.data.data()});
    }
    auto tail = std::make_unique<DecodingTail>(
        path, impl.model, impl.split, inputs,
        std::vector<std::string>{config.box_output, config.logit_output});
    for (std::size_t output = 0; output < 2; ++output) {
      const auto& shape = tail->output_shape(output);
      if (shape.size() < 2 || shape[0] != batch) {
        throw model_error("the output '" + (output == 0 ? config.box_output : config.logit_output) +
                          "' is not per image (" + shape_text(shape) + " at batch " +
                          std::to_string(batch) + ")");
      }
    }
    return tail;
  };
  impl.single_tail = tail_for(1);
  if (max_batch > 1) impl.batched_tail = tail_for(max_batch);
  impl.last_tail = impl.single_tail.get();
  // The buffers never move: set up once, each run only invokes.
  std::vector<xnn_external_value> externals{{kInputExternalId, impl.input.data()}};
  for (Piece& piece : impl.pieces) externals.push_back({piece.id, piece.data.data()});
  for (const auto& [name, id] : impl.probes) {
    (void)name;
    if (id == kInputExternalId || piece_of.count(id)) continue;  // buffers of their own
    auto& data = impl.probe_data[id];
    data.assign(max_batch * piece_sizes.at(id), 0.F);
    externals.push_back({id, data.data()});
  }
  for (xnn_runtime_t runtime : {impl.single_pooled.get(), impl.single_inline.get(),
                                impl.batched_pooled.get(), impl.batched_inline.get()}) {
    if (runtime &&
        xnn_setup_runtime(runtime, externals.size(), externals.data()) != xnn_status_success) {
      throw model_error("XNNPACK cannot set up the network's buffers");
    }
  }
  std::map<std::string, int> ops;
  for (const auto& node : graph.node()) ++ops[node.op_type()];
  std::ostringstream text;
  text << "XNNPACK subgraph of " << graph.node_size() << " ONNX nodes (";
  bool first = true;
  for (const auto& [op, n] : ops) {
    text << (first ? "" : ", ") << n << " " << op;
    first = false;
  }
  text << ")" << (int8 ? ", int8 (ranges " + config.int8_ranges.string() + ")" : std::string())
       << (config.record_ranges ? ", recording ranges" : "") << ", batch 1"
       << (max_batch > 1 ? " and " + std::to_string(max_batch) : std::string()) << ", " << threads
       << " thread(s)"
       << (config.threads > threads
               ? " (" + std::to_string(config.threads) + " asked; the CPUs this process may use)"
               : std::string())
       << (impl.pool ? ", the pool used while faster than one thread (measured pass by pass)" : "")
       << (impl.split.empty() ? std::string()
                              : ", then a decoding tail of " +
                                    std::to_string(impl.split.tail_nodes) + " nodes on the host");
  impl.summary = text.str();
}

XnnpackNetwork::~XnnpackNetwork() = default;

float* XnnpackNetwork::input(int slot) {
  const auto size = static_cast<std::size_t>(impl_->config.input_size);
  return impl_->input.data() + static_cast<std::size_t>(slot) * size * size * 3;
}

void XnnpackNetwork::run(int count) {
  Impl& impl = *impl_;
  const bool batched = count > 1 && impl.batched_inline;
  PoolGovernor& governor = batched ? impl.batched_governor : impl.single_governor;
  const bool pooled = impl.pool && governor.use_pool();
  xnn_runtime_t runtime = batched ? (pooled ? impl.batched_pooled : impl.batched_inline).get()
                                  : (pooled ? impl.single_pooled : impl.single_inline).get();
  const auto start = std::chrono::steady_clock::now();
  if (xnn_invoke_runtime(runtime) != xnn_status_success) {
    throw std::runtime_error("XNNPACK failed to run the network");
  }
  if (impl.pool) {
    governor.record(std::chrono::duration_cast<std::chrono::nanoseconds>(
                        std::chrono::steady_clock::now() - start)
                        .count());
  }
  if (!impl.probes.empty()) record_ranges(count);
  // The concatenations the network ends with, image by image; then the decoding tail.
  for (JoinedOutput& joined : impl.joined) {
    for (int image = 0; image < count; ++image) {
      float* to = joined.data.data() + static_cast<std::size_t>(image) * joined.per_image;
      for (const std::size_t index : joined.piece_indices) {
        const Piece& piece = impl.pieces[index];
        const float* from = piece.data.data() + static_cast<std::size_t>(image) * piece.per_image;
        to = std::copy(from, from + piece.per_image, to);
      }
    }
  }
  impl.last_tail = (batched ? impl.batched_tail : impl.single_tail).get();
  impl.last_tail->run();
}

void XnnpackNetwork::record_ranges(int count) {
  Impl& impl = *impl_;
  const auto image_floats =
      static_cast<std::size_t>(impl.config.input_size) * impl.config.input_size * 3;
  for (const auto& [name, id] : impl.probes) {
    const float* data = nullptr;
    std::size_t size = 0;
    if (id == kInputExternalId) {
      data = impl.input.data();
      size = image_floats;
    } else if (const auto probe = impl.probe_data.find(id); probe != impl.probe_data.end()) {
      data = probe->second.data();
      size = probe->second.size() / static_cast<std::size_t>(std::max(1, impl.config.max_batch));
    } else {
      for (const Piece& piece : impl.pieces) {
        if (piece.id == id) {
          data = piece.data.data();
          size = piece.per_image;
        }
      }
    }
    if (!data || size == 0) continue;
    const auto [low, high] =
        std::minmax_element(data, data + size * static_cast<std::size_t>(count));
    auto [range, fresh] = impl.recorded.try_emplace(name, ActivationRange{*low, *high});
    if (!fresh) {
      range->second.min = std::min(range->second.min, *low);
      range->second.max = std::max(range->second.max, *high);
    }
  }
}

ActivationRanges XnnpackNetwork::recorded_ranges() const {
  ActivationRanges ranges;
  ranges.model_sha256 = impl_->model_sha256;
  ranges.tensors = impl_->recorded;
  return ranges;
}

void XnnpackNetwork::clear_recorded_ranges() {
  impl_->recorded.clear();
}

const float* XnnpackNetwork::boxes() const {
  return impl_->last_tail->output(0);
}
const float* XnnpackNetwork::logits() const {
  return impl_->last_tail->output(1);
}
std::size_t XnnpackNetwork::anchors() const {
  const auto& shape = impl_->single_tail->output_shape(0);
  return product(shape, 1) / std::max<std::size_t>(shape.back(), 1);
}
std::size_t XnnpackNetwork::classes() const {
  return impl_->single_tail->output_shape(1).back();
}
std::string XnnpackNetwork::summary() const {
  return impl_->summary;
}

std::string XnnpackNetwork::pool_use() const {
  if (!impl_->pool) return "";
  std::ostringstream text;
  text.precision(3);
  for (const auto& [name, governor] : {std::pair{"batch 1", &impl_->single_governor},
                                       std::pair{"batch", &impl_->batched_governor}}) {
    if (governor->passes() == 0) continue;
    text << (text.tellp() > 0 ? "; " : "") << name << ": " << governor->pooled_passes() << " of "
         << governor->passes() << " passes on the pool (estimates: pool "
         << static_cast<double>(governor->pooled_ns()) * 1e-6 << " ms, one thread "
         << static_cast<double>(governor->inline_ns()) * 1e-6 << " ms)";
  }
  return text.str();
}

}  // namespace rtmot::detector
