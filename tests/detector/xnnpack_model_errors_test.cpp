// The XNNPACK backend on models it cannot build: a clear start-up error naming what (operator and
// node, input shape, weight tensor), exit code bad_model; under backend auto the detector runs on
// OpenCV's CPU path instead and says why. The bad models are the real one changed through ONNX's
// own protobuf classes (libonnx), as a re-export would change it.
#include <gtest/gtest.h>
#include <onnx/onnx_pb.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/model_check.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/xnnpack_network.hpp"
#include "shared_data.hpp"
#include "vtest_frames.hpp"

namespace rtmot::detector {
namespace {

namespace fs = std::filesystem;

class XnnpackModelErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
    if (!fs::exists(model)) FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
    std::ifstream in(model, std::ios::binary);
    ASSERT_TRUE(model_.ParseFromIstream(&in));
    dir_ = fs::temp_directory_path() /
           ("rtmot-xnnpack-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes the changed model; the config reads it with the real anchors (no checksum file).
  SsdConfig write(BackendRequest backend) {
    const fs::path path = dir_ / "changed.onnx";
    std::ofstream out(path, std::ios::binary);
    EXPECT_TRUE(model_.SerializeToOstream(&out));
    out.close();
    SsdConfig config;
    config.model_path = path;
    config.anchors_path = test::source_path("models/ssdlite_mobilenet_v2_coco.anchors.csv");
    config.backend = backend;
    config.threads = 1;
    config.verify_checksums = false;
    return config;
  }

  static InputError expect_error(const SsdConfig& config) {
    try {
      SsdDetector detector(config);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error";
    return InputError("", 0, "", "none");
  }

  onnx::NodeProto& first_node(const std::string& op) {
    for (auto& node : *model_.mutable_graph()->mutable_node()) {
      if (node.op_type() == op) return node;
    }
    throw std::logic_error("no " + op);
  }

  static bool attribute_named(const onnx::NodeProto& node, const std::string& name) {
    for (const auto& attribute : node.attribute()) {
      if (attribute.name() == name) return true;
    }
    return false;
  }

  onnx::ModelProto model_;
  fs::path dir_;
};

// Sum of two inputs is Add to ONNX (and to OpenCV's importer), but not an operator the XNNPACK
// backend builds.
TEST_F(XnnpackModelErrors, UnsupportedOperatorIsNamed) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  onnx::NodeProto& node = first_node("Add");
  node.set_op_type("Sum");
  const std::string name = node.name();
  const InputError e = expect_error(write(BackendRequest::xnnpack));
  EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
  EXPECT_NE(std::string(e.what()).find("'Sum'"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("changed.onnx"), std::string::npos) << e.what();
}

TEST_F(XnnpackModelErrors, AutoFallsBackToOpenCvFromAnUnsupportedOperator) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  const auto caps = probe_backend_capabilities();
  if (caps.opencv_has_cuda && caps.cuda_devices > 0) {
    GTEST_SKIP() << "CUDA here: backend auto picks cuda, not xnnpack (checked on CPU machines)";
  }
  first_node("Add").set_op_type("Sum");
  SsdDetector fallback(write(BackendRequest::automatic));  // one thread: auto picks xnnpack
  EXPECT_EQ(fallback.backend().engine, Engine::opencv);
  EXPECT_EQ(fallback.backend().name, "cpu");
  EXPECT_NE(fallback.backend().reason.find("'Sum'"), std::string::npos)
      << fallback.backend().reason;
  EXPECT_NE(fallback.describe().find("xnnpack cannot run the model"), std::string::npos)
      << fallback.describe();
  // And it detects: the same network, on OpenCV.
  cv::Mat image(576, 768, CV_8UC3, cv::Scalar(90, 120, 150));
  std::vector<tracker::Detection> out;
  EXPECT_NO_THROW(fallback.detect(image, 1, out));
}

TEST_F(XnnpackModelErrors, WrongInputShapeIsAStartUpError) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  auto* dims = model_.mutable_graph()
                   ->mutable_input(0)
                   ->mutable_type()
                   ->mutable_tensor_type()
                   ->mutable_shape()
                   ->mutable_dim();
  ASSERT_EQ(dims->size(), 4);
  dims->Mutable(2)->set_dim_value(320);
  dims->Mutable(3)->set_dim_value(320);
  const InputError e = expect_error(write(BackendRequest::xnnpack));
  EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
  EXPECT_NE(std::string(e.what()).find("x3x320x320"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("300x300"), std::string::npos) << e.what();
}

TEST_F(XnnpackModelErrors, NonFiniteWeightsNameTheTensor) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  onnx::NodeProto& conv = first_node("Conv");
  const std::string weights = conv.input(1);
  for (auto& tensor : *model_.mutable_graph()->mutable_initializer()) {
    if (tensor.name() != weights) continue;
    ASSERT_FALSE(tensor.raw_data().empty());
    std::string raw = tensor.raw_data();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(raw.data() + 4 * 7, &nan, sizeof nan);  // one weight of many
    tensor.set_raw_data(raw);
  }
  const InputError e = expect_error(write(BackendRequest::xnnpack));
  EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
  EXPECT_NE(std::string(e.what()).find("'" + weights + "'"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
}

TEST_F(XnnpackModelErrors, UnsupportedAttributeIsNamed) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  onnx::NodeProto& transpose = first_node("Transpose");
  for (auto& attribute : *transpose.mutable_attribute()) {
    if (attribute.name() == "perm") {
      attribute.clear_ints();
      for (const int axis : {0, 3, 1, 2}) attribute.add_ints(axis);
    }
  }
  const InputError e = expect_error(write(BackendRequest::xnnpack));
  EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
  EXPECT_NE(std::string(e.what()).find(transpose.name()), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("perm"), std::string::npos) << e.what();
}

// Sizes the file declares are bounded before anything is allocated from them (issue 32: pads of
// 2^30 made the build throw std::bad_alloc, exit 1). Each case: bad_model, one line, naming the
// file and the node or tensor.
void expect_bad_model(const InputError& e, const std::string& names, const std::string& what) {
  const std::string text = e.what();
  EXPECT_EQ(e.exit_code(), ExitCode::bad_model) << text;
  EXPECT_NE(text.find("changed.onnx"), std::string::npos) << text;
  EXPECT_NE(text.find(names), std::string::npos) << text;
  EXPECT_NE(text.find(what), std::string::npos) << text;
  EXPECT_EQ(text.find('\n'), std::string::npos) << text;
}

void set_ints(onnx::NodeProto& node, const std::string& name, std::vector<std::int64_t> values) {
  for (auto& attribute : *node.mutable_attribute()) {
    if (attribute.name() != name) continue;
    attribute.clear_ints();
    for (const auto v : values) attribute.add_ints(v);
    return;
  }
  auto* attribute = node.add_attribute();
  attribute->set_name(name);
  attribute->set_type(onnx::AttributeProto::INTS);
  for (const auto v : values) attribute->add_ints(v);
}

// torch.onnx writes pytorch-ssd's `view(x.size(0), -1, k)` as Shape, Gather, Unsqueeze and Concat
// feeding the Reshape: shapes that are constants once the input size is known. The bundled model's
// head Reshapes rewritten so: the heads' reshapes and their Concat move to the host tail (shapes
// computed once), and the detections are the unchanged model's on XNNPACK.
TEST_F(XnnpackModelErrors, ComputedReshapesAsTorchWritesThemRunInTheTail) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  const SsdConfig original = write(BackendRequest::xnnpack);
  onnx::GraphProto& graph = *model_.mutable_graph();
  const auto int64_constant = [&](const std::string& name, std::vector<std::int64_t> values,
                                  bool scalar) {
    onnx::TensorProto& tensor = *graph.add_initializer();
    tensor.set_name(name);
    tensor.set_data_type(onnx::TensorProto::INT64);
    if (!scalar) tensor.add_dims(static_cast<std::int64_t>(values.size()));
    for (const auto v : values) tensor.add_int64_data(v);
  };
  std::vector<onnx::NodeProto> nodes;
  int rewritten = 0;
  for (const onnx::NodeProto& node : graph.node()) {
    if (node.op_type() != "Reshape") {
      nodes.push_back(node);
      continue;
    }
    const std::string tag = "dyn" + std::to_string(rewritten++);
    std::int64_t columns = 0;
    for (const auto& init : graph.initializer()) {
      if (init.name() == node.input(1)) columns = init.int64_data_size() ? init.int64_data(2) : 0;
    }
    if (columns == 0) {  // raw_data
      for (const auto& init : graph.initializer()) {
        if (init.name() != node.input(1)) continue;
        std::int64_t values[3];
        std::memcpy(values, init.raw_data().data(), sizeof(values));
        columns = values[2];
      }
    }
    ASSERT_GT(columns, 0) << node.name();
    int64_constant(tag + "_zero", {0}, true);
    int64_constant(tag + "_rest", {-1, columns}, false);
    const auto add = [&](const std::string& op, std::vector<std::string> inputs,
                         const std::string& output) {
      onnx::NodeProto made;
      made.set_name(tag + "_" + op);
      made.set_op_type(op);
      for (const auto& input : inputs) made.add_input(input);
      made.add_output(output);
      nodes.push_back(made);
      return &nodes.back();
    };
    add("Shape", {node.input(0)}, tag + "_shape");
    add("Gather", {tag + "_shape", tag + "_zero"}, tag + "_batch");
    onnx::NodeProto* unsqueeze = add("Unsqueeze", {tag + "_batch"}, tag + "_batch1");
    auto* axes = unsqueeze->add_attribute();
    axes->set_name("axes");
    axes->set_type(onnx::AttributeProto::INTS);
    axes->add_ints(0);
    onnx::NodeProto* concat = add("Concat", {tag + "_batch1", tag + "_rest"}, tag + "_target");
    auto* axis = concat->add_attribute();
    axis->set_name("axis");
    axis->set_type(onnx::AttributeProto::INT);
    axis->set_i(0);
    onnx::NodeProto reshape = node;
    reshape.set_input(1, tag + "_target");
    nodes.push_back(reshape);
  }
  EXPECT_EQ(rewritten, 12);
  graph.clear_node();
  for (const auto& node : nodes) *graph.add_node() = node;
  const fs::path changed = dir_ / "computed.onnx";
  {
    std::ofstream out(changed, std::ios::binary);
    ASSERT_TRUE(model_.SerializeToOstream(&out));
  }
  SsdConfig config = original;
  config.model_path = changed;
  config.classes = {};
  SsdConfig reference_config = original;
  reference_config.classes = {};
  SsdDetector computed(config);
  SsdDetector reference(reference_config);
  // 12 heads x (Shape, Gather, Unsqueeze, Concat, Reshape), the two Concats, the two Identities.
  EXPECT_NE(computed.describe().find("decoding tail of 64 nodes"), std::string::npos)
      << computed.describe();
  std::size_t compared = 0;
  // Under qemu one frame (a forward takes ~15 s there).
  const std::set<int> numbers = test::under_emulation() ? std::set<int>{1} : std::set<int>{1, 101};
  for (const auto& [number, image] : test::vtest_frames(numbers)) {
    std::vector<tracker::Detection> expected;
    std::vector<tracker::Detection> found;
    reference.detect(image, number, expected);
    computed.detect(image, number, found);
    ASSERT_EQ(found.size(), expected.size()) << "frame " << number;
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(found[i].class_id, expected[i].class_id);
      EXPECT_EQ(found[i].score, expected[i].score);
      EXPECT_EQ(found[i].box.x, expected[i].box.x);
      ++compared;
    }
  }
  EXPECT_GE(compared, 5U);
}

// torch.onnx without constant folding writes constants as Constant nodes, not initializers: the
// bundled model's head reshapes' target shapes moved into Constant nodes build as before, with no
// tail, and give the same detections.
TEST_F(XnnpackModelErrors, ConstantNodesBuildAsInitializersDo) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  SsdConfig reference_config = write(BackendRequest::xnnpack);
  reference_config.classes = {};
  SsdDetector reference(reference_config);  // loaded before the file is rewritten
  onnx::GraphProto& graph = *model_.mutable_graph();
  std::vector<onnx::NodeProto> constants;
  std::vector<onnx::TensorProto> kept;
  for (const auto& tensor : graph.initializer()) {
    if (tensor.data_type() != onnx::TensorProto::INT64) {
      kept.push_back(tensor);
      continue;
    }
    onnx::NodeProto node;
    node.set_name(tensor.name() + "_constant");
    node.set_op_type("Constant");
    node.add_output(tensor.name());
    auto* value = node.add_attribute();
    value->set_name("value");
    value->set_type(onnx::AttributeProto::TENSOR);
    *value->mutable_t() = tensor;
    constants.push_back(node);
  }
  ASSERT_EQ(constants.size(), 12U);  // the heads' reshape targets
  std::vector<onnx::NodeProto> nodes(constants);
  nodes.insert(nodes.end(), graph.node().begin(), graph.node().end());
  graph.clear_node();
  for (const auto& node : nodes) *graph.add_node() = node;
  graph.clear_initializer();
  for (const auto& tensor : kept) *graph.add_initializer() = tensor;
  SsdConfig config = write(BackendRequest::xnnpack);
  config.classes = {};
  SsdDetector changed(config);
  EXPECT_EQ(changed.describe().find("decoding tail"), std::string::npos) << changed.describe();
  std::size_t compared = 0;
  for (const auto& [number, image] : test::vtest_frames({1})) {
    std::vector<tracker::Detection> expected;
    std::vector<tracker::Detection> found;
    reference.detect(image, number, expected);
    changed.detect(image, number, found);
    ASSERT_EQ(found.size(), expected.size());
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(found[i].score, expected[i].score);
      ++compared;
    }
  }
  EXPECT_GE(compared, 5U);
}

// A per-channel constant scale in the middle of the network (as an unfolded batch norm is): not an
// operator XNNPACK's builder takes, and a convolution follows, so it is no decoding tail: the error
// names the node where the host would have to take over.
TEST_F(XnnpackModelErrors, APerChannelScaleBeforeAConvolutionIsNamed) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  onnx::GraphProto& graph = *model_.mutable_graph();
  const onnx::NodeProto conv = first_node("Conv");
  std::int64_t channels = 0;
  for (const auto& tensor : graph.initializer()) {
    if (tensor.name() == conv.input(1)) channels = tensor.dims(0);
  }
  ASSERT_GT(channels, 0);
  onnx::TensorProto& scale = *graph.add_initializer();
  scale.set_name("per_channel_scale");
  scale.set_data_type(onnx::TensorProto::FLOAT);
  for (const std::int64_t dim : {std::int64_t{1}, channels, std::int64_t{1}, std::int64_t{1}}) {
    scale.add_dims(dim);
  }
  for (std::int64_t c = 0; c < channels; ++c) scale.add_float_data(1.F);
  for (auto& node : *graph.mutable_node()) {
    for (auto& input : *node.mutable_input()) {
      if (input == conv.output(0)) input = "scaled";
    }
  }
  std::vector<onnx::NodeProto> nodes(graph.node().begin(), graph.node().end());
  onnx::NodeProto mul;
  mul.set_name("scale_first");
  mul.set_op_type("Mul");
  mul.add_input(conv.output(0));
  mul.add_input("per_channel_scale");
  mul.add_output("scaled");
  const auto after = std::find_if(nodes.begin(), nodes.end(), [&](const onnx::NodeProto& n) {
    return n.output_size() > 0 && n.output(0) == conv.output(0);
  });
  nodes.insert(after + 1, mul);
  graph.clear_node();
  for (const auto& node : nodes) *graph.add_node() = node;
  expect_bad_model(expect_error(write(BackendRequest::xnnpack)), "node 'scale_first' (Mul)",
                   "which the xnnpack backend runs only on the host");
}

// After the network XNNPACK builds, the engine runs a decoding tail on the host (pytorch-ssd's box
// decoding and softmax: model_layout_test.cpp); an operator the tail does not run is named, with
// its node and the model, and model check reports the same. The class logits pass through Tanh
// (which OpenCV runs) before leaving the graph.
TEST_F(XnnpackModelErrors, AnOperatorTheDecodingTailDoesNotRunIsNamed) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  onnx::GraphProto& graph = *model_.mutable_graph();
  for (auto& node : *graph.mutable_node()) {
    for (auto& output : *node.mutable_output()) {
      if (output == "class_logits") output = "raw_logits";
    }
  }
  onnx::NodeProto& tanh = *graph.add_node();
  tanh.set_name("squash_logits");
  tanh.set_op_type("Tanh");
  tanh.add_input("raw_logits");
  tanh.add_output("class_logits");
  const SsdConfig config = write(BackendRequest::xnnpack);
  const InputError e = expect_error(config);
  expect_bad_model(e, "node 'squash_logits' (Tanh)", "op 'Tanh' in the decoding tail");
  // Model check runs OpenCV's engine five times: not under qemu (~15 s a forward there).
  if (test::under_emulation()) return;

  const ModelCheck check = check_model({config.model_path, config.anchors_path, {}});
  const std::string report = format_model_check(check);
  EXPECT_TRUE(check.usable()) << report;  // OpenCV runs it
  EXPECT_NE(report.find("engine     xnnpack: no: " + config.model_path.string() +
                        ": node 'squash_logits' (Tanh): op 'Tanh' in the decoding tail"),
            std::string::npos)
      << report;
}

TEST_F(XnnpackModelErrors, HugePadsAreABadModel) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  for (const std::int64_t pad : {std::int64_t{1} << 30, std::int64_t{1} << 62}) {
    onnx::NodeProto& conv = first_node("Conv");
    set_ints(conv, "pads", {pad, pad, pad, pad});
    expect_bad_model(expect_error(write(BackendRequest::xnnpack)), conv.name(), "pads");
  }
}

// Pads within the bound on each side, but a feature map of 60300 x 60300 x 32 floats.
TEST_F(XnnpackModelErrors, AHugeFeatureMapIsABadModel) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  set_ints(first_node("Conv"), "pads", {60000, 60000, 60000, 60000});
  expect_bad_model(expect_error(write(BackendRequest::xnnpack)), "' would be 1x",
                   "floats; at most");
}

TEST_F(XnnpackModelErrors, HugeStridesDilationsAndGroupsAreABadModel) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  const std::int64_t huge = std::int64_t{1} << 40;
  {
    onnx::NodeProto& conv = first_node("Conv");
    set_ints(conv, "dilations", {huge, huge});
    expect_bad_model(expect_error(write(BackendRequest::xnnpack)), conv.name(), "dilations");
    set_ints(conv, "dilations", {1, 1});
    set_ints(conv, "strides", {huge, 1});
    expect_bad_model(expect_error(write(BackendRequest::xnnpack)), conv.name(), "strides");
    set_ints(conv, "strides", {2, 2});
  }
  onnx::NodeProto& conv = first_node("Conv");
  for (auto& attribute : *conv.mutable_attribute()) {
    if (attribute.name() == "group") attribute.set_i(huge);
  }
  if (!attribute_named(conv, "group")) {
    auto* group = conv.add_attribute();
    group->set_name("group");
    group->set_type(onnx::AttributeProto::INT);
    group->set_i(huge);
  }
  expect_bad_model(expect_error(write(BackendRequest::xnnpack)), conv.name(), "group");
}

// A weight tensor declaring 2^40 output channels and a zero dimension holds no values and so
// matches its (empty) data: the declared size itself must be refused before the bias is sized.
TEST_F(XnnpackModelErrors, AHugeDeclaredWeightDimensionIsABadModel) {
  if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  const std::string weights = first_node("Conv").input(1);
  for (auto& tensor : *model_.mutable_graph()->mutable_initializer()) {
    if (tensor.name() != weights) continue;
    tensor.clear_dims();
    for (const std::int64_t dim :
         {std::int64_t{1} << 40, std::int64_t{0}, std::int64_t{3}, std::int64_t{3}}) {
      tensor.add_dims(dim);
    }
    tensor.clear_raw_data();
  }
  expect_bad_model(expect_error(write(BackendRequest::xnnpack)), "'" + weights + "'",
                   "declares a dimension of 1099511627776");
}

}  // namespace
}  // namespace rtmot::detector
