#pragma once
// The XNNPACK engine's host-side end: the ONNX nodes after the last operator the engine builds in
// XNNPACK (a model's decoding tail, such as pytorch-ssd's box decoding and softmax), run on the
// host in fp32 by a small interpreter of elementwise and shape operators.
//
// Why an interpreter and not a recogniser of "the SSD decode": real exports of one decode differ
// in form. pytorch-ssd's `convert_locations_to_boxes` + `center_form_to_corner_form` come out of
// torch.onnx with or without constant folding (the priors' slices and the variances multiplied
// into constants, or left as Slice/Mul nodes), as Div by 2 or Mul by 0.5, with opset 9's Slice
// attributes or opset 10's inputs, Softmax before or after other nodes; our own fixture decodes
// TF's way (per-anchor constants, sigmoid). A pattern matcher would have to list every variant and
// extract constants it assumes the meaning of; running the nodes as written gives exactly what the
// graph computes for any arrangement of these operators, and an operator outside the set is
// named. The work is small next to the network (about 30 passes over [anchors, 4] and one softmax
// over [anchors, classes]), and every buffer is sized when the tail is planned: a pass allocates
// nothing.
//
// Its definitions: xnnpack_tail_split.cpp (split_decoding_tail, decoding_tail_operators),
// xnnpack_decoding_tail.cpp (DecodingTail: planning, run()) and the planner's files
// (xnnpack_tail_planner.hpp; the loop over elements that the steps run: xnnpack_tail_tensors.hpp).
#include <onnx/onnx_pb.h>

#include <cstddef>
#include <deque>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rtmot::detector {

/// The operators the tail runs, for messages and docs.
const char* decoding_tail_operators();

/// Which nodes XNNPACK builds and which the host runs after it.
struct TailSplit {
  std::vector<bool> on_host;          // per node of the graph: in the tail (or a constant)
  std::vector<std::string> boundary;  // tensors XNNPACK computes that the host reads
  std::size_t tail_nodes{0};          // nodes run per pass on the host (constants excluded)
  bool empty() const { return tail_nodes == 0; }
};

/// Walks the graph in order: a node belongs to the network while XNNPACK's builder takes it and
/// its inputs come from the network; the first that does not, and every node reading what it
/// computes, belong to the tail. Throws rtmot::InputError (bad_model) naming the model, the node
/// and the operator when the tail holds an operator the host does not run ("op 'X' in the decoding
/// tail"), or when the network proper does (an operator XNNPACK lacks before a convolution).
TailSplit split_decoding_tail(const std::filesystem::path& model, const onnx::GraphProto& graph,
                              const char* network_operators);

/// A tensor the tail reads from the network: name, ONNX shape (batch first), its floats.
struct TailInput {
  std::string name;
  std::vector<std::size_t> shape;
  const float* data;
};

/// One batch size's tail, planned once. Not copyable (its steps point into its own buffers).
class DecodingTail {
 public:
  /// Plans the tail's nodes (split.on_host, in graph order) reading `inputs` and producing
  /// `outputs`; constants (initializers, Constant nodes, and nodes of constants only) are
  /// computed here once. Throws rtmot::InputError (bad_model) naming the model and the node.
  DecodingTail(const std::filesystem::path& model, const onnx::ModelProto& onnx_model,
               const TailSplit& split, const std::vector<TailInput>& inputs,
               const std::vector<std::string>& outputs);
  DecodingTail(const DecodingTail&) = delete;
  DecodingTail& operator=(const DecodingTail&) = delete;

  /// Runs every step on the inputs' current values. Allocates nothing.
  void run() const;
  const float* output(std::size_t index) const { return outputs_[index].data; }
  const std::vector<std::size_t>& output_shape(std::size_t index) const {
    return outputs_[index].shape;
  }

  struct Tensor {
    std::vector<std::size_t> shape;
    const float* data{nullptr};
    bool constant{false};
    bool integer{false};  // an int64 constant (indices, shapes, axes)
    std::vector<std::int64_t> integers;
  };

 private:
  std::deque<std::vector<float>> buffers_;  // a deque: growing it moves no buffer
  std::vector<std::function<void()>> steps_;
  std::vector<Tensor> outputs_;
};

}  // namespace rtmot::detector
