#pragma once
// The XNNPACK engine's translation of the ONNX graph (docs/cpu-detector.md): SubgraphBuilder
// walks the network's nodes (those TailSplit leaves to XNNPACK) and defines the XNNPACK values and
// nodes of one subgraph, one batch size, fp32 or int8. Its definitions are in three files:
// xnnpack_subgraph_builder.cpp (the walk, the input, tensors and weights),
// xnnpack_subgraph_operators.cpp (one member per ONNX operator) and xnnpack_subgraph_int8.cpp
// (the int8 engine's tensors and weights). Internal to detector/.
#include <onnx/onnx_pb.h>
#include <xnnpack.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/input_error.hpp"
#include "detector/activation_ranges.hpp"
#include "detector/xnnpack_decoding_tail.hpp"
#include "detector/xnnpack_quantization.hpp"

namespace rtmot::detector::xnnpack {

/// The input's external id (external_outputs numbers the others from 1).
constexpr uint32_t kInputExternalId = 0;

struct SubgraphDeleter {
  void operator()(xnn_subgraph_t subgraph) const { xnn_delete_subgraph(subgraph); }
};
using SubgraphPtr = std::unique_ptr<xnn_subgraph, SubgraphDeleter>;

/// A tensor as the builder tracks it.
struct Value {
  uint32_t id{XNN_INVALID_VALUE_ID};
  std::vector<std::size_t> shape;  // as ONNX sees it
  /// A 4-D feature map that ONNX sees as NCHW and XNNPACK holds as NHWC.
  bool nchw{false};
  /// False after a Reshape: XNNPACK still has the old shape (a reshape of contiguous data moves
  /// nothing, so none is run); only host-side consumers (Concat, the graph's outputs) may read it.
  bool xnn_shape{true};
  /// Set on a Concat's result: the external outputs it joins, in order (host side).
  std::vector<uint32_t> pieces;
  /// Signed 8-bit (the int8 engine): real = scale * (q - zero_point).
  bool qs8{false};
  float scale{1.F};
  std::int32_t zero_point{0};
};

/// What the builder does besides fp32: quantize (ranges set) or record ranges (probes set).
struct BuildMode {
  const ActivationRanges* ranges{nullptr};
  const std::filesystem::path* ranges_path{nullptr};
  QuantizedWeights* quantized{nullptr};
  std::map<std::string, uint32_t>* probes{nullptr};  // tensor -> its external id
};

/// Builds one subgraph (one batch size) from the parsed model. The converted weights live in
/// `weights`, shared by every subgraph built from the model and alive as long as the runtimes.
class SubgraphBuilder {
 public:
  SubgraphBuilder(const std::filesystem::path& path, const onnx::GraphProto& graph,
                  const TailSplit& split, std::map<std::string, std::vector<float>>& weights,
                  const std::map<std::string, uint32_t>& external_ids, std::size_t batch,
                  std::size_t input_size, BuildMode mode);

  /// The subgraph of the network's nodes (the split's others run on the host); `outputs` gets
  /// the value of each tensor the host reads (pieces set).
  SubgraphPtr build(std::map<std::string, Value>& outputs,
                    std::map<uint32_t, std::size_t>& external_sizes);

 private:
  // --- errors, the input (xnnpack_subgraph_builder.cpp) ---

  InputError model_error(const std::string& problem) const;
  InputError error(const onnx::NodeProto& node, const std::string& problem) const;
  void check(xnn_status status, const std::string& what) const;

  void define_input();

  // --- the int8 engine (xnnpack_subgraph_int8.cpp) ---

  Quantization quantization_of(const std::string& tensor) const;

  /// The tensor as int8: itself, or (the fp32 input, an fp32 graph output read again) converted
  /// once per subgraph.
  Value quantized(const std::string& tensor, const Value& value);

  uint32_t define_quantized(const std::string& name, const std::vector<std::size_t>& xnn_dims,
                            Quantization q);

  /// An int8 node's result `name`: its int8 tensor (defined here, into `into`), and the value the
  /// graph reads, which is fp32 (converted) where the tensor is an output the host reads.
  Value quantized_result(const std::string& name, const std::vector<std::size_t>& onnx_shape,
                         bool nchw, uint32_t& into);

  /// The converts to fp32 outputs, defined after their producer (XNNPACK runs nodes in order).
  void flush_converts(const std::string& what);

  /// A convolution's weights for the int8 engine, in XNNPACK's layouts (as the fp32 ones below):
  /// int8 per output channel, and the bias as int32 at scale input_scale * channel_scale.
  std::pair<uint32_t, uint32_t> quantized_weights(const onnx::NodeProto& node,
                                                  const std::vector<float>& weights,
                                                  const std::vector<float>& bias, float input_scale,
                                                  bool depthwise,
                                                  const std::vector<std::size_t>& w);

  // --- the nodes' inputs, the tensors defined (xnnpack_subgraph_builder.cpp) ---

  const Value& value_of(const onnx::NodeProto& node, int input) const;
  const Value& xnn_value_of(const onnx::NodeProto& node, int input) const;
  const onnx::TensorProto& initializer(const onnx::NodeProto& node, int input) const;
  std::vector<float> floats(const onnx::NodeProto& node, const onnx::TensorProto& tensor) const;
  std::vector<std::int64_t> int64s(const onnx::NodeProto& node,
                                   const onnx::TensorProto& tensor) const;

  /// A static tensor on converted weights, made once per model and shared by every batch size.
  uint32_t define_static(const std::string& key, const std::vector<std::size_t>& dims,
                         const std::vector<float>& data);

  /// Every tensor the builder defines is bounded (fp32 or int8).
  void check_size(const std::string& name, const std::vector<std::size_t>& xnn_dims) const;

  /// A computed tensor: an external output when it is (a piece of) a graph output, or recorded.
  uint32_t define_computed(const std::string& name, const std::vector<std::size_t>& xnn_dims);

  std::vector<std::size_t> xnn_dims(const Value& value) const;

  // --- the operators (xnnpack_subgraph_operators.cpp) ---

  /// The bounds of a Clip or Relu node.
  std::pair<float, float> clamp_bounds(const onnx::NodeProto& node) const;

  /// The Clip/Relu right after a Conv that is its output's only reader: XNNPACK clamps in the
  /// convolution's own output loop, saving a pass over the feature map.
  /// Its node index, or -1.
  int fusable_activation(const onnx::NodeProto& conv) const;

  void conv(const onnx::NodeProto& node, const onnx::NodeProto* activation);

  /// The input (0 or 1) of a binary node that is a one-value initializer, or -1.
  int scalar_operand(const onnx::NodeProto& node) const;

  /// A tensor and a scalar constant (a model's own input normalisation, as the fixture of
  /// pytorch-ssd's interface has), broadcast by XNNPACK. fp32 in both engines: in the int8 one
  /// such a node may only read an fp32 tensor (the input), and the convolution after it converts.
  void scalar_arithmetic(const onnx::NodeProto& node);

  void clamp(const onnx::NodeProto& node);

  void add(const onnx::NodeProto& node);

  // NCHW -> NHWC is what XNNPACK holds already: nothing to run.
  void transpose(const onnx::NodeProto& node);

  void reshape(const onnx::NodeProto& node);

  // Joined on the host (see XnnpackNetwork::run): each input is an external output. Axis 1 of
  // [N, ...] keeps each image's rows of one input contiguous, so the join is a copy per image.
  void concat(const onnx::NodeProto& node);

  const std::filesystem::path& path_;
  const onnx::GraphProto& graph_;
  const TailSplit& split_;
  std::map<std::string, std::vector<float>>& weights_;
  const std::map<std::string, uint32_t>& external_ids_;
  std::size_t batch_;
  std::size_t input_size_;
  BuildMode mode_;
  uint32_t next_probe_id_{0};
  std::map<std::string, Value> converted_;  // int8 copies of fp32 tensors, by tensor name
  std::vector<std::pair<uint32_t, uint32_t>> pending_converts_;
  std::map<std::string, const onnx::TensorProto*> initializers_;
  std::map<std::string, int> consumers_;
  std::map<std::string, int> reader_;  // a node reading the tensor (the only one where it matters)
  std::map<std::string, Value> values_;
  std::map<uint32_t, std::size_t> external_sizes_;
  xnn_subgraph_t subgraph_{nullptr};
};

/// The tensors that must be XNNPACK external outputs: what the tensors the host reads come from
/// once the moves that run nothing here (Identity, Reshape, Transpose, Concat) are looked through.
std::map<std::string, uint32_t> external_outputs(const onnx::GraphProto& graph,
                                                 const std::vector<std::string>& read);

}  // namespace rtmot::detector::xnnpack
