#include "detector/xnnpack_decoding_tail.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "common/input_error.hpp"

namespace rtmot::detector {

const char* decoding_tail_operators() {
  return "Slice, Mul, Add, Sub, Div, Exp, Sigmoid, Softmax, Concat, Reshape, Unsqueeze, Squeeze, "
         "Flatten, Identity, Constant; Shape, Gather, Cast on shapes (computed once)";
}

namespace {

using Tensor = DecodingTail::Tensor;
using Shape = std::vector<std::size_t>;
constexpr std::size_t kMaxRank = 8;  // of a tensor the tail computes

const std::set<std::string>& tail_operators() {
  static const std::set<std::string> ops{"Slice",     "Mul",     "Add",     "Sub",      "Div",
                                         "Exp",       "Sigmoid", "Softmax", "Concat",   "Reshape",
                                         "Unsqueeze", "Squeeze", "Flatten", "Identity", "Constant",
                                         "Shape",     "Gather",  "Cast"};
  return ops;
}

// What XNNPACK's builder (xnnpack_network.cpp) takes, by operator and by where its inputs come
// from; kept beside the split so that the two agree.
bool builder_operator(const std::string& op) {
  static const std::set<std::string> ops{"Conv", "Clip",      "Relu",    "Add",    "Mul",     "Sub",
                                         "Div",  "Transpose", "Reshape", "Concat", "Identity"};
  return ops.count(op) != 0;
}

bool is_binary(const std::string& op) {
  return op == "Add" || op == "Mul" || op == "Sub" || op == "Div";
}

std::size_t element_count(const onnx::TensorProto& tensor) {
  std::size_t n = 1;
  for (const auto dim : tensor.dims())
    n *= static_cast<std::size_t>(std::max<std::int64_t>(dim, 0));
  return n;
}

std::size_t product(const Shape& shape, std::size_t from = 0,
                    std::size_t to = std::numeric_limits<std::size_t>::max()) {
  const std::size_t end = std::min(to, shape.size());
  if (from >= end) return 1;
  return std::accumulate(shape.begin() + static_cast<std::ptrdiff_t>(from),
                         shape.begin() + static_cast<std::ptrdiff_t>(end), std::size_t{1},
                         std::multiplies<>());
}

std::string shape_text(const Shape& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + "]";
}

std::vector<std::size_t> strides_of(const Shape& shape) {
  std::vector<std::size_t> strides(shape.size(), 1);
  for (std::size_t i = shape.size(); i-- > 1;) strides[i - 1] = strides[i] * shape[i];
  return strides;
}

// Visits every element of `shape` in order, with each operand's offset (its strides, 0 along a
// broadcast axis): the innermost axis as a plain loop, the others by an odometer.
template <std::size_t N, typename Visit>
void for_each_element(const Shape& shape, const std::array<std::vector<std::size_t>, N>& strides,
                      Visit visit) {
  const std::size_t rank = shape.size();
  if (product(shape) == 0) return;
  if (rank == 0) {
    std::array<std::size_t, N> offsets{};
    visit(std::size_t{0}, offsets, std::size_t{1}, offsets);
    return;
  }
  std::array<std::size_t, kMaxRank> index{};
  std::array<std::size_t, N> base{};
  std::array<std::size_t, N> inner{};
  for (std::size_t k = 0; k < N; ++k) inner[k] = strides[k][rank - 1];
  const std::size_t row = shape[rank - 1];
  std::size_t out = 0;
  while (true) {
    visit(out, base, row, inner);
    out += row;
    std::size_t axis = rank - 1;
    while (axis-- > 0) {
      ++index[axis];
      for (std::size_t k = 0; k < N; ++k) base[k] += strides[k][axis];
      if (index[axis] < shape[axis]) break;
      for (std::size_t k = 0; k < N; ++k) base[k] -= strides[k][axis] * shape[axis];
      index[axis] = 0;
    }
    if (axis == SIZE_MAX) return;
  }
}

const onnx::AttributeProto* attribute(const onnx::NodeProto& node, const char* name) {
  for (const auto& a : node.attribute()) {
    if (a.name() == name) return &a;
  }
  return nullptr;
}

int model_opset(const onnx::ModelProto& model) {
  for (const auto& entry : model.opset_import()) {
    if (entry.domain().empty() || entry.domain() == "ai.onnx") {
      return static_cast<int>(entry.version());
    }
  }
  return 1;
}

/// Plans one tail: every tensor by name, steps appended in graph order.
class Planner {
 public:
  Planner(const std::filesystem::path& model, int opset, std::deque<std::vector<float>>& buffers,
          std::vector<std::function<void()>>& steps)
      : model_(model), opset_(opset), buffers_(buffers), steps_(steps) {}

  void add_initializer(const onnx::TensorProto& tensor) {
    tensors_[tensor.name()] = constant_of(tensor, "initializer '" + tensor.name() + "'");
  }
  void add_input(const TailInput& input) {
    Tensor tensor;
    tensor.shape = input.shape;
    tensor.data = input.data;
    tensors_[input.name] = tensor;
  }
  const Tensor& find(const std::string& name, const onnx::NodeProto* node) const {
    const auto found = tensors_.find(name);
    if (found == tensors_.end()) {
      throw problem(node, "reads '" + name + "', which neither the network nor the tail computes");
    }
    return found->second;
  }

  void plan(const onnx::NodeProto& node) {
    const std::string& op = node.op_type();
    if (op == "Constant") {
      constant_node(node);
    } else if (op == "Identity") {
      alias(node, input(node, 0).shape);
    } else if (op == "Reshape") {
      reshape(node);
    } else if (op == "Unsqueeze" || op == "Squeeze") {
      squeeze(node, op == "Unsqueeze");
    } else if (op == "Flatten") {
      flatten(node);
    } else if (is_binary(op)) {
      binary(node);
    } else if (op == "Exp" || op == "Sigmoid") {
      unary(node);
    } else if (op == "Softmax") {
      softmax(node);
    } else if (op == "Slice") {
      slice(node);
    } else if (op == "Concat" && input(node, 0).integer) {
      integer_concat(node);
    } else if (op == "Concat") {
      concat(node);
    } else if (op == "Shape") {
      shape_of(node);
    } else if (op == "Gather") {
      gather(node);
    } else if (op == "Cast") {
      cast(node);
    } else {
      throw problem(&node, "op '" + op +
                               "' in the decoding tail is run neither by XNNPACK nor by " +
                               "the host (it runs " + decoding_tail_operators() + ")");
    }
  }

  InputError problem(const onnx::NodeProto* node, const std::string& what) const {
    const std::string where =
        node ? "node '" + node->name() + "' (" + node->op_type() + ") of the decoding tail: "
             : std::string("the decoding tail: ");
    return InputError(model_.string(), 0, "", where + what, ExitCode::bad_model);
  }

 private:
  const Tensor& input(const onnx::NodeProto& node, int index) const {
    if (index >= node.input_size() || node.input(index).empty()) {
      throw problem(&node, "input " + std::to_string(index) + " missing");
    }
    return find(node.input(index), &node);
  }
  const Tensor& floats_input(const onnx::NodeProto& node, int index) const {
    const Tensor& tensor = input(node, index);
    if (tensor.integer) throw problem(&node, "integer arithmetic is not run by the tail");
    return tensor;
  }
  std::vector<std::int64_t> integers_input(const onnx::NodeProto& node, int index) const {
    const Tensor& tensor = input(node, index);
    if (!tensor.integer)
      throw problem(&node, "input '" + node.input(index) + "' must be int64 constants");
    return tensor.integers;
  }
  std::vector<std::int64_t> ints_attribute(const onnx::NodeProto& node, const char* name) const {
    const auto* a = attribute(node, name);
    if (!a) return {};
    return {a->ints().begin(), a->ints().end()};
  }
  std::int64_t axis_in(const onnx::NodeProto& node, std::int64_t axis, std::size_t rank) const {
    const auto r = static_cast<std::int64_t>(rank);
    if (axis < 0) axis += r;
    if (axis < 0 || axis >= r) {
      throw problem(&node, "axis " + std::to_string(axis) + " outside a tensor of rank " +
                               std::to_string(rank));
    }
    return axis;
  }

  Tensor constant_of(const onnx::TensorProto& proto, const std::string& what) {
    Tensor tensor;
    tensor.constant = true;
    for (const auto dim : proto.dims()) {
      if (dim < 0 || dim > (std::int64_t{1} << 24)) {
        throw problem(nullptr, what + " declares a dimension of " + std::to_string(dim));
      }
      tensor.shape.push_back(static_cast<std::size_t>(dim));
    }
    const std::size_t count = element_count(proto);
    const std::string& raw = proto.raw_data();
    if (proto.data_type() == onnx::TensorProto::FLOAT) {
      auto& data = buffers_.emplace_back(count, 0.F);
      if (!raw.empty() && raw.size() == count * sizeof(float)) {
        std::memcpy(data.data(), raw.data(), raw.size());
      } else if (raw.empty() && static_cast<std::size_t>(proto.float_data_size()) == count) {
        std::copy(proto.float_data().begin(), proto.float_data().end(), data.begin());
      } else {
        throw problem(nullptr,
                      what + " holds the wrong number of values for " + shape_text(tensor.shape));
      }
      tensor.data = data.data();
    } else if (proto.data_type() == onnx::TensorProto::INT64) {
      tensor.integer = true;
      tensor.integers.resize(count);
      if (!raw.empty() && raw.size() == count * sizeof(std::int64_t)) {
        std::memcpy(tensor.integers.data(), raw.data(), raw.size());
      } else if (raw.empty() && static_cast<std::size_t>(proto.int64_data_size()) == count) {
        std::copy(proto.int64_data().begin(), proto.int64_data().end(), tensor.integers.begin());
      } else {
        throw problem(nullptr,
                      what + " holds the wrong number of values for " + shape_text(tensor.shape));
      }
    } else {
      throw problem(nullptr, what + " is neither float32 nor int64");
    }
    return tensor;
  }

  // A computed tensor of `shape`: its buffer, and whether its step runs now (all inputs
  // constant: the value is a constant) or every pass.
  Tensor& result(const onnx::NodeProto& node, const Shape& shape, bool constant) {
    if (product(shape) > (std::size_t{1} << 26) || shape.size() > kMaxRank) {
      throw problem(&node, "would compute " + shape_text(shape) + " values");
    }
    Tensor& tensor = tensors_[node.output(0)];
    tensor = Tensor();
    tensor.shape = shape;
    tensor.constant = constant;
    tensor.data = buffers_.emplace_back(product(shape), 0.F).data();
    return tensor;
  }
  void schedule(bool constant, std::function<void()> step) {
    if (constant) {
      step();
    } else {
      steps_.push_back(std::move(step));
    }
  }
  float* writable(const Tensor& tensor) const { return const_cast<float*>(tensor.data); }

  void constant_node(const onnx::NodeProto& node) {
    Tensor tensor;
    if (const auto* a = attribute(node, "value")) {
      tensor = constant_of(a->t(), "the constant '" + node.output(0) + "'");
    } else if (const auto* f = attribute(node, "value_float")) {
      tensor.constant = true;
      tensor.data = buffers_.emplace_back(1, f->f()).data();
    } else if (const auto* fs = attribute(node, "value_floats")) {
      tensor.constant = true;
      tensor.shape = {static_cast<std::size_t>(fs->floats_size())};
      tensor.data = buffers_.emplace_back(fs->floats().begin(), fs->floats().end()).data();
    } else if (const auto* i = attribute(node, "value_int")) {
      tensor.constant = tensor.integer = true;
      tensor.integers = {i->i()};
    } else if (const auto* is = attribute(node, "value_ints")) {
      tensor.constant = tensor.integer = true;
      tensor.shape = {static_cast<std::size_t>(is->ints_size())};
      tensor.integers.assign(is->ints().begin(), is->ints().end());
    } else {
      throw problem(&node, "a Constant of a kind the tail does not read");
    }
    tensors_[node.output(0)] = tensor;
  }

  // The same values under another shape: no step.
  void alias(const onnx::NodeProto& node, const Shape& shape) {
    Tensor tensor = input(node, 0);
    if (product(shape) != product(tensor.shape)) {
      throw problem(&node, "cannot view " + shape_text(tensor.shape) + " as " + shape_text(shape));
    }
    tensor.shape = shape;
    tensors_[node.output(0)] = tensor;
  }

  void reshape(const onnx::NodeProto& node) {
    const Shape& from = input(node, 0).shape;
    const auto wanted = opset_ < 5 ? ints_attribute(node, "shape") : integers_input(node, 1);
    Shape shape(wanted.size(), 1);
    int infer = -1;
    for (std::size_t i = 0; i < wanted.size(); ++i) {
      if (wanted[i] == -1 && infer < 0) {
        infer = static_cast<int>(i);
      } else if (wanted[i] == 0 && i < from.size()) {
        shape[i] = from[i];
      } else if (wanted[i] > 0) {
        shape[i] = static_cast<std::size_t>(wanted[i]);
      } else {
        throw problem(&node, "invalid target shape");
      }
    }
    if (infer >= 0) {
      const std::size_t known = product(shape);
      shape[static_cast<std::size_t>(infer)] = known ? product(from) / known : 0;
    }
    alias(node, shape);
  }

  void squeeze(const onnx::NodeProto& node, bool unsqueeze) {
    const Shape& from = input(node, 0).shape;
    std::vector<std::int64_t> axes = opset_ < 13 ? ints_attribute(node, "axes")
                                     : node.input_size() > 1 && !node.input(1).empty()
                                         ? integers_input(node, 1)
                                         : std::vector<std::int64_t>{};
    Shape shape;
    if (unsqueeze) {
      const std::size_t rank = from.size() + axes.size();
      std::vector<bool> inserted(rank, false);
      for (const auto axis : axes)
        inserted[static_cast<std::size_t>(axis_in(node, axis, rank))] = true;
      std::size_t next = 0;
      for (std::size_t i = 0; i < rank; ++i) shape.push_back(inserted[i] ? 1 : from.at(next++));
    } else {
      std::vector<bool> removed(from.size(), axes.empty());
      for (const auto axis : axes) {
        removed[static_cast<std::size_t>(axis_in(node, axis, from.size()))] = true;
      }
      for (std::size_t i = 0; i < from.size(); ++i) {
        if (!removed[i] || from[i] != 1) shape.push_back(from[i]);
      }
    }
    if (input(node, 0).integer) {  // index arithmetic on constants: the values stay
      Tensor tensor = input(node, 0);
      tensor.shape = shape;
      tensors_[node.output(0)] = tensor;
      return;
    }
    alias(node, shape);
  }

  void flatten(const onnx::NodeProto& node) {
    const Shape& from = input(node, 0).shape;
    const auto* a = attribute(node, "axis");
    const std::int64_t at = a ? a->i() : 1;
    const auto axis = static_cast<std::size_t>(
        at == static_cast<std::int64_t>(from.size()) ? at : axis_in(node, at, from.size()));
    alias(node, {product(from, 0, axis), product(from, axis)});
  }

  void binary(const onnx::NodeProto& node) {
    const Tensor a = floats_input(node, 0);
    const Tensor b = floats_input(node, 1);
    const std::size_t rank = std::max(a.shape.size(), b.shape.size());
    Shape shape(rank, 1);
    std::array<std::vector<std::size_t>, 2> strides{std::vector<std::size_t>(rank, 0),
                                                    std::vector<std::size_t>(rank, 0)};
    std::size_t k = 0;
    for (const Tensor* operand : {&a, &b}) {
      const auto own = strides_of(operand->shape);
      const std::size_t shift = rank - operand->shape.size();
      for (std::size_t i = 0; i < operand->shape.size(); ++i) {
        const std::size_t dim = operand->shape[i];
        std::size_t& out = shape[shift + i];
        if (dim != 1 && out != 1 && dim != out) {
          throw problem(&node,
                        "cannot broadcast " + shape_text(a.shape) + " with " + shape_text(b.shape));
        }
        if (dim != 1) out = dim;
        strides[k][shift + i] = dim == 1 ? 0 : own[i];
      }
      ++k;
    }
    const bool constant = a.constant && b.constant;
    float* out = writable(result(node, shape, constant));
    const float* x = a.data;
    const float* y = b.data;
    const auto run = [=](auto f) {
      return [=] {
        for_each_element<2>(shape, strides,
                            [&](std::size_t at, const std::array<std::size_t, 2>& base,
                                std::size_t row, const std::array<std::size_t, 2>& step) {
                              const float* p = x + base[0];
                              const float* q = y + base[1];
                              for (std::size_t i = 0; i < row; ++i)
                                out[at + i] = f(p[i * step[0]], q[i * step[1]]);
                            });
      };
    };
    const std::string& op = node.op_type();
    if (op == "Add") {
      schedule(constant, run([](float p, float q) { return p + q; }));
    } else if (op == "Sub") {
      schedule(constant, run([](float p, float q) { return p - q; }));
    } else if (op == "Mul") {
      schedule(constant, run([](float p, float q) { return p * q; }));
    } else {
      schedule(constant, run([](float p, float q) { return p / q; }));
    }
  }

  void unary(const onnx::NodeProto& node) {
    const Tensor a = floats_input(node, 0);
    float* out = writable(result(node, a.shape, a.constant));
    const float* x = a.data;
    const std::size_t n = product(a.shape);
    if (node.op_type() == "Exp") {
      schedule(a.constant, [=] {
        for (std::size_t i = 0; i < n; ++i) out[i] = std::exp(x[i]);
      });
    } else {
      schedule(a.constant, [=] {
        for (std::size_t i = 0; i < n; ++i) out[i] = 1.F / (1.F + std::exp(-x[i]));
      });
    }
  }

  // Opset 13's Softmax normalises along one axis; earlier ones over the axes from `axis` on
  // (the input seen as 2-D), their default axis 1.
  void softmax(const onnx::NodeProto& node) {
    const Tensor a = floats_input(node, 0);
    const auto* at = attribute(node, "axis");
    const std::size_t axis = static_cast<std::size_t>(
        axis_in(node, at ? at->i() : (opset_ < 13 ? 1 : -1), a.shape.size()));
    const std::size_t outer = product(a.shape, 0, axis);
    const std::size_t length = opset_ < 13 ? product(a.shape, axis) : a.shape[axis];
    const std::size_t inner = opset_ < 13 ? 1 : product(a.shape, axis + 1);
    float* out = writable(result(node, a.shape, a.constant));
    const float* x = a.data;
    schedule(a.constant, [=] {
      for (std::size_t o = 0; o < outer; ++o) {
        for (std::size_t i = 0; i < inner; ++i) {
          const std::size_t first = o * length * inner + i;
          float largest = -std::numeric_limits<float>::infinity();
          for (std::size_t k = 0; k < length; ++k)
            largest = std::max(largest, x[first + k * inner]);
          float sum = 0.F;
          for (std::size_t k = 0; k < length; ++k) {
            out[first + k * inner] = std::exp(x[first + k * inner] - largest);
            sum += out[first + k * inner];
          }
          for (std::size_t k = 0; k < length; ++k) out[first + k * inner] /= sum;
        }
      }
    });
  }

  void slice(const onnx::NodeProto& node) {
    const Tensor a = floats_input(node, 0);
    const std::size_t rank = a.shape.size();
    std::vector<std::int64_t> starts;
    std::vector<std::int64_t> ends;
    std::vector<std::int64_t> axes;
    std::vector<std::int64_t> steps;
    if (opset_ < 10) {
      starts = ints_attribute(node, "starts");
      ends = ints_attribute(node, "ends");
      axes = ints_attribute(node, "axes");
    } else {
      starts = integers_input(node, 1);
      ends = integers_input(node, 2);
      if (node.input_size() > 3 && !node.input(3).empty()) axes = integers_input(node, 3);
      if (node.input_size() > 4 && !node.input(4).empty()) steps = integers_input(node, 4);
    }
    if (axes.empty()) {
      for (std::size_t i = 0; i < starts.size(); ++i) axes.push_back(static_cast<std::int64_t>(i));
    }
    if (steps.empty()) steps.assign(starts.size(), 1);
    if (ends.size() != starts.size() || axes.size() != starts.size() ||
        steps.size() != starts.size()) {
      throw problem(&node, "starts, ends, axes and steps of different lengths");
    }
    Shape shape = a.shape;
    std::vector<std::size_t> first(rank, 0);
    std::vector<std::size_t> stride(rank, 1);
    for (std::size_t i = 0; i < starts.size(); ++i) {
      const auto axis = static_cast<std::size_t>(axis_in(node, axes[i], rank));
      if (steps[i] < 1) throw problem(&node, "only positive steps are run by the tail");
      const auto dim = static_cast<std::int64_t>(a.shape[axis]);
      const auto clamp = [dim](std::int64_t v) {
        return std::clamp(v < 0 ? v + dim : v, std::int64_t{0}, dim);
      };
      const std::int64_t begin = clamp(starts[i]);
      const std::int64_t end = clamp(ends[i]);
      first[axis] = static_cast<std::size_t>(begin);
      stride[axis] = static_cast<std::size_t>(steps[i]);
      shape[axis] =
          end > begin ? static_cast<std::size_t>((end - begin + steps[i] - 1) / steps[i]) : 0;
    }
    const auto own = strides_of(a.shape);
    std::size_t offset = 0;
    std::array<std::vector<std::size_t>, 1> strides{std::vector<std::size_t>(rank)};
    for (std::size_t i = 0; i < rank; ++i) {
      offset += first[i] * own[i];
      strides[0][i] = own[i] * stride[i];
    }
    float* out = writable(result(node, shape, a.constant));
    const float* x = a.data + offset;
    schedule(a.constant, [=] {
      for_each_element<1>(shape, strides,
                          [&](std::size_t at, const std::array<std::size_t, 1>& base,
                              std::size_t row, const std::array<std::size_t, 1>& step) {
                            for (std::size_t i = 0; i < row; ++i)
                              out[at + i] = x[base[0] + i * step[0]];
                          });
    });
  }

  // Shapes are known when the tail is planned: torch.onnx's `view(x.size(0), -1, k)` (Shape,
  // Gather, Unsqueeze, Concat, then Reshape) becomes constants here.
  void shape_of(const onnx::NodeProto& node) {
    const Shape& from = input(node, 0).shape;
    Tensor tensor;
    tensor.constant = tensor.integer = true;
    const auto rank = static_cast<std::int64_t>(from.size());
    const auto* s = attribute(node, "start");
    const auto* e = attribute(node, "end");
    const auto clamp = [rank](std::int64_t v) {
      return std::clamp(v < 0 ? v + rank : v, std::int64_t{0}, rank);
    };
    const std::int64_t first = s ? clamp(s->i()) : 0;
    const std::int64_t last = e ? clamp(e->i()) : rank;
    for (std::int64_t i = first; i < last; ++i) {
      tensor.integers.push_back(static_cast<std::int64_t>(from[static_cast<std::size_t>(i)]));
    }
    tensor.shape = {tensor.integers.size()};
    tensors_[node.output(0)] = tensor;
  }

  void gather(const onnx::NodeProto& node) {
    const auto data = integers_input(node, 0);
    const Tensor& indices = input(node, 1);
    const auto* a = attribute(node, "axis");
    if (!indices.integer || input(node, 0).shape.size() != 1 || (a && a->i() != 0)) {
      throw problem(&node, "the tail gathers only from a 1-D int64 constant (a shape)");
    }
    Tensor tensor;
    tensor.constant = tensor.integer = true;
    tensor.shape = indices.shape;
    for (auto index : indices.integers) {
      const auto size = static_cast<std::int64_t>(data.size());
      if (index < 0) index += size;
      if (index < 0 || index >= size) throw problem(&node, "index outside the shape");
      tensor.integers.push_back(data[static_cast<std::size_t>(index)]);
    }
    tensors_[node.output(0)] = tensor;
  }

  void cast(const onnx::NodeProto& node) {
    const auto* to = attribute(node, "to");
    const Tensor& from = input(node, 0);
    const bool same = to && ((from.integer && to->i() == onnx::TensorProto::INT64) ||
                             (!from.integer && to->i() == onnx::TensorProto::FLOAT));
    if (!same) throw problem(&node, "the tail casts only int64 to int64 and float to float");
    tensors_[node.output(0)] = from;
  }

  void integer_concat(const onnx::NodeProto& node) {
    Tensor tensor;
    tensor.constant = tensor.integer = true;
    for (int i = 0; i < node.input_size(); ++i) {
      const auto part = integers_input(node, i);
      if (input(node, i).shape.size() > 1) throw problem(&node, "joins shapes of rank 1 only");
      tensor.integers.insert(tensor.integers.end(), part.begin(), part.end());
    }
    tensor.shape = {tensor.integers.size()};
    tensors_[node.output(0)] = tensor;
  }

  void concat(const onnx::NodeProto& node) {
    const auto* a = attribute(node, "axis");
    if (!a) throw problem(&node, "no axis");
    std::vector<Tensor> parts;
    for (int i = 0; i < node.input_size(); ++i) parts.push_back(floats_input(node, i));
    const std::size_t rank = parts.front().shape.size();
    const auto axis = static_cast<std::size_t>(axis_in(node, a->i(), rank));
    Shape shape = parts.front().shape;
    shape[axis] = 0;
    bool constant = true;
    for (const Tensor& part : parts) {
      Shape other = part.shape;
      if (other.size() != rank) throw problem(&node, "inputs of different ranks");
      shape[axis] += other[axis];
      other[axis] = shape[axis];
      Shape mine = shape;
      if (other != mine) {
        throw problem(&node, "inputs " + shape_text(parts.front().shape) + " and " +
                                 shape_text(part.shape) + " differ outside axis " +
                                 std::to_string(axis));
      }
      constant = constant && part.constant;
    }
    const std::size_t outer = product(shape, 0, axis);
    std::vector<std::pair<const float*, std::size_t>> pieces;  // data, floats per outer index
    for (const Tensor& part : parts) pieces.emplace_back(part.data, product(part.shape, axis));
    const std::size_t row = product(shape, axis);
    float* out = writable(result(node, shape, constant));
    schedule(constant, [=] {
      for (std::size_t o = 0; o < outer; ++o) {
        float* to = out + o * row;
        for (const auto& [data, size] : pieces)
          to = std::copy(data + o * size, data + (o + 1) * size, to);
      }
    });
  }

  const std::filesystem::path& model_;
  int opset_;
  std::deque<std::vector<float>>& buffers_;
  std::vector<std::function<void()>>& steps_;
  std::map<std::string, Tensor> tensors_;
};

InputError split_error(const std::filesystem::path& model, const onnx::NodeProto& node,
                       const std::string& problem) {
  return InputError(model.string(), 0, "",
                    "node '" + node.name() + "' (" + node.op_type() + "): " + problem,
                    ExitCode::bad_model);
}

}  // namespace

TailSplit split_decoding_tail(const std::filesystem::path& model, const onnx::GraphProto& graph,
                              const char* network_operators) {
  // reshaped: a Reshape's result, which XNNPACK still holds in the old shape (only a Concat or the
  // host may read it); joined: a Concat's, assembled on the host from XNNPACK's outputs.
  enum class Source { network, reshaped, joined, host, constant };
  std::map<std::string, Source> source;
  for (const auto& tensor : graph.initializer()) source[tensor.name()] = Source::constant;
  const auto source_of = [&](const std::string& name) {
    const auto found = source.find(name);
    return found == source.end() ? Source::network : found->second;  // the input
  };
  std::map<std::string, std::size_t> constant_sizes;  // initializers and Constant nodes' values
  for (const auto& tensor : graph.initializer())
    constant_sizes[tensor.name()] = element_count(tensor);
  for (const auto& node : graph.node()) {
    const auto* value = node.op_type() == "Constant" ? attribute(node, "value") : nullptr;
    if (value && node.output_size() == 1)
      constant_sizes[node.output(0)] = element_count(value->t());
  }
  const auto scalar_constant = [&](const std::string& name) {
    const auto found = constant_sizes.find(name);
    return found != constant_sizes.end() && found->second == 1;
  };
  TailSplit split;
  split.on_host.assign(static_cast<std::size_t>(graph.node_size()), false);
  std::set<std::string> boundary;
  bool convolution = false;  // a convolution among the nodes run on the host: no decoding tail
  int first_host = -1;       // the node where the host takes over
  for (int index = 0; index < graph.node_size(); ++index) {
    const onnx::NodeProto& node = graph.node(index);
    const std::string& op = node.op_type();
    bool any_host = false;
    bool any_joined = false;
    bool any_reshaped = false;
    bool all_constant = true;
    std::vector<std::string> computed;
    for (const auto& name : node.input()) {
      if (name.empty()) continue;
      const Source from = source_of(name);
      any_host = any_host || from == Source::host;
      any_joined = any_joined || from == Source::joined;
      any_reshaped = any_reshaped || from == Source::reshaped;
      all_constant = all_constant && from == Source::constant;
      if (from == Source::network || from == Source::reshaped || from == Source::joined) {
        computed.push_back(name);
      }
    }
    Source result = Source::network;
    if (all_constant) {
      result = Source::constant;  // Constant nodes, the priors' slices: computed once
    } else if (any_host || !builder_operator(op)) {
      result = Source::host;
    } else if (is_binary(op)) {
      // XNNPACK's builder: Add of two computed tensors, or any of the four with a scalar
      // constant; a per-anchor constant (the anchors' centres) belongs to the decoding.
      const bool scalar = node.input_size() == 2 &&
                          (scalar_constant(node.input(0)) || scalar_constant(node.input(1)));
      const bool two_computed = computed.size() == 2 && op == "Add";
      result =
          (scalar || two_computed) && !any_joined && !any_reshaped ? Source::network : Source::host;
    } else if (op == "Concat") {
      const auto* axis = attribute(node, "axis");
      result = axis && axis->i() == 1 && !any_joined ? Source::joined : Source::host;
    } else if (op == "Reshape") {
      result = any_joined ? Source::host : Source::reshaped;
    } else if (op == "Identity") {
      result = source_of(node.input(0));
    } else if (any_joined || any_reshaped) {
      result = Source::host;  // XNNPACK's operators read tensors in XNNPACK's own shape
    }
    if (result == Source::host || result == Source::constant) {
      split.on_host[static_cast<std::size_t>(index)] = true;
      for (const auto& name : computed) boundary.insert(name);
    }
    if (result == Source::host) {
      ++split.tail_nodes;
      if (first_host < 0) first_host = index;
      convolution = convolution || op == "Conv";
    }
    for (const auto& name : node.output()) source[name] = result;
  }
  for (const auto& output : graph.output()) {
    const Source from = source_of(output.name());
    if (from == Source::network || from == Source::reshaped || from == Source::joined) {
      boundary.insert(output.name());
    }
  }
  split.boundary.assign(boundary.begin(), boundary.end());
  // An operator neither side runs: named as the network's (a convolution follows it: it is no
  // decoding tail) or as the tail's.
  for (int index = 0; index < graph.node_size(); ++index) {
    if (!split.on_host[static_cast<std::size_t>(index)]) continue;
    const onnx::NodeProto& node = graph.node(index);
    if (tail_operators().count(node.op_type())) continue;
    if (!convolution) {
      throw split_error(model, node,
                        "op '" + node.op_type() + "' in the decoding tail: XNNPACK's engine runs " +
                            "after the network only " + decoding_tail_operators() +
                            " (on the host): use backend: cpu");
    }
    if (builder_operator(node.op_type())) {
      const onnx::NodeProto& cause = graph.node(first_host);
      throw split_error(model, node,
                        "follows node '" + cause.name() + "' (" + cause.op_type() +
                            "), which the xnnpack backend runs only on the host (it builds " +
                            network_operators +
                            "; Add, Mul, Sub, Div only with one-value "
                            "constants; nothing after a Concat or a Reshape but the heads' "
                            "join): use backend: cpu");
    }
    throw split_error(model, node,
                      "operator '" + node.op_type() +
                          "' is not supported by the xnnpack backend (it builds " +
                          network_operators + "): use backend: cpu");
  }
  return split;
}

DecodingTail::DecodingTail(const std::filesystem::path& model, const onnx::ModelProto& onnx_model,
                           const TailSplit& split, const std::vector<TailInput>& inputs,
                           const std::vector<std::string>& outputs) {
  const onnx::GraphProto& graph = onnx_model.graph();
  Planner planner(model, model_opset(onnx_model), buffers_, steps_);
  std::set<std::string> read;
  for (int index = 0; index < graph.node_size(); ++index) {
    if (!split.on_host[static_cast<std::size_t>(index)]) continue;
    for (const auto& name : graph.node(index).input()) read.insert(name);
  }
  for (const auto& tensor : graph.initializer()) {
    if (read.count(tensor.name())) planner.add_initializer(tensor);
  }
  for (const TailInput& input : inputs) planner.add_input(input);
  for (int index = 0; index < graph.node_size(); ++index) {
    if (split.on_host[static_cast<std::size_t>(index)]) planner.plan(graph.node(index));
  }
  for (const std::string& name : outputs) {
    const Tensor& tensor = planner.find(name, nullptr);
    if (tensor.integer || tensor.constant) {
      throw planner.problem(nullptr, "the output '" + name + "' is a constant");
    }
    outputs_.push_back(tensor);
  }
}

void DecodingTail::run() const {
  for (const auto& step : steps_) step();
}

}  // namespace rtmot::detector
