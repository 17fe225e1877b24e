#include "detector/model_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <new>
#include <opencv2/core.hpp>
#include <opencv2/dnn/dnn.hpp>
#include <sstream>

#include "common/input_error.hpp"
#include "detector/activation_ranges.hpp"
#include "detector/dnn_backend.hpp"
#include "detector/label_table.hpp"
#include "detector/model_checksum.hpp"
#include "detector/model_files.hpp"
#include "detector/ssd_anchors.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/xnnpack_network.hpp"

namespace rtmot::detector {
namespace {

constexpr int kTimedPasses = 5;

std::vector<int> shape_of(const cv::Mat& mat) {
  return std::vector<int>(mat.size.p, mat.size.p + mat.dims);
}

std::string shape_text(const std::vector<int>& shape) {
  return fmt::format("[{}]", fmt::join(shape, ", "));
}

std::string checksum_state(ModelCheck& check) {
  const auto file = checksum_path_of(check.model);
  try {
    const int checked = verify_model_checksums(file, check.model, check.anchors_file);
    if (checked == 0) return "none (no " + file.filename().string() + " beside the model)";
    return fmt::format("verified: {} file(s) against {}", checked, file.string());
  } catch (const InputError& e) {
    check.problems.push_back(std::string("checksums: ") + e.what());
    return "FAILED";
  }
}

// The outputs as OpenCV computes them for a grey input of `images` images, by name.
std::vector<NamedShape> run_outputs(cv::dnn::Net& net, int images, int size) {
  const int shape[] = {images, 3, size, size};
  const cv::Mat blob(4, shape, CV_32F, cv::Scalar(0.F));  // 0 is mid-grey after normalisation
  net.setInput(blob);
  const std::vector<cv::String> names = net.getUnconnectedOutLayersNames();
  std::vector<cv::Mat> outputs;
  net.forward(outputs, names);
  std::vector<NamedShape> found;
  for (std::size_t i = 0; i < names.size() && i < outputs.size(); ++i) {
    found.push_back({names[i], shape_of(outputs[i])});
  }
  return found;
}

const NamedShape* output_named(const std::vector<NamedShape>& outputs, const char* name) {
  const auto at = std::find_if(outputs.begin(), outputs.end(),
                               [&](const NamedShape& o) { return o.name == name; });
  return at == outputs.end() ? nullptr : &*at;
}

// The model's interface through OpenCV's importer: outputs for one image and for two.
void inspect_outputs(ModelCheck& check) {
  cv::dnn::Net net;
  const int size = check.description.input_size;
  try {
    net = cv::dnn::readNetFromONNX(check.model.string());
    check.outputs = run_outputs(net, 1, size);
  } catch (const cv::Exception& e) {
    std::string why = e.err;
    std::replace(why.begin(), why.end(), '\n', ' ');
    check.problems.push_back("model: OpenCV cannot load or run it: " + why);
    return;
  } catch (const std::bad_alloc&) {  // declared sizes beyond this machine's memory
    check.problems.push_back("model: it asks for more memory than this machine gives (damaged?)");
    return;
  }
  const ModelDescription& described = check.description;
  const char* box_name = described.box_output.c_str();
  const char* score_name = described.score_output.c_str();
  const NamedShape* boxes = output_named(check.outputs, box_name);
  const NamedShape* classes = output_named(check.outputs, score_name);
  if (boxes == nullptr || classes == nullptr) {
    std::vector<std::string> names;
    for (const auto& o : check.outputs) names.push_back(o.name + " " + shape_text(o.shape));
    check.problems.push_back(fmt::format(
        "outputs: expected {} [1, anchors, 4] and {} [1, anchors, classes]{}; this model's are "
        "{}{}",
        box_name, score_name, " (" + described_by(described) + ")", fmt::join(names, ", "),
        described.file.empty()
            ? "; another model describes itself in " + description_path_of(check.model).string() +
                  " or its metadata (docs/model.md)"
            : ""));
    return;
  }
  if (boxes->shape.size() != 3 || boxes->shape[0] != 1 || boxes->shape[2] != 4) {
    check.problems.push_back(fmt::format("outputs.boxes: {} has shape {}, not [1, anchors, 4]",
                                         box_name, shape_text(boxes->shape)));
    return;
  }
  check.anchors_in_model = boxes->shape[1];
  if (classes->shape.size() != 3 || classes->shape[0] != 1 ||
      classes->shape[1] != check.anchors_in_model) {
    check.problems.push_back(fmt::format("outputs.scores: {} has shape {}, not [1, {}, classes]",
                                         score_name, shape_text(classes->shape),
                                         check.anchors_in_model));
    return;
  }
  check.class_columns = classes->shape[2];
  if (check.class_columns != check.label_columns) {
    check.problems.push_back(fmt::format("labels: {} class columns in the model, {} names in {}",
                                         check.class_columns, check.label_columns, check.labels));
  }
  try {
    const auto pair = run_outputs(net, 2, size);
    const NamedShape* batched = output_named(pair, box_name);
    check.batch_dimension = batched != nullptr && !batched->shape.empty() && batched->shape[0] == 2;
  } catch (const cv::Exception&) {
    check.batch_dimension = false;  // a fixed batch of one refuses two images: reported as "no"
  }
}

void check_anchors(ModelCheck& check) {
  if (check.description.layout != OutputLayout::deltas) return;  // the boxes come decoded
  try {
    check.anchors_in_file = static_cast<int>(read_anchors(check.anchors_file).size());
  } catch (const InputError& e) {
    check.problems.push_back(std::string("anchors: ") + e.what());
    return;
  }
  if (check.anchors_in_model > 0 && check.anchors_in_file != check.anchors_in_model) {
    check.problems.push_back(fmt::format("anchors: {} has {} rows, the model's outputs {}",
                                         check.anchors_file.string(), check.anchors_in_file,
                                         check.anchors_in_model));
  }
}

EngineCheck run_engine(const ModelCheck& check, BackendRequest backend) {
  EngineCheck result{std::string(kBackendNames.name(backend)), false, ""};
  try {
    SsdConfig config;
    config.model_path = check.model;
    config.anchors_path = check.anchors_file;
    config.int8_ranges = check.int8_ranges;
    config.backend = backend;
    config.classes = {};
    config.verify_checksums = false;  // reported on their own line
    SsdDetector detector(config);
    const int size = check.description.input_size;
    const cv::Mat grey(size, size, CV_8UC3, cv::Scalar(128, 128, 128));
    std::vector<tracker::Detection> found;
    std::vector<double> ms;
    for (int pass = 0; pass < kTimedPasses; ++pass) {
      detector.detect(grey, pass, found);
      ms.push_back(static_cast<double>(detector.last_forward_ns()) * 1e-6);
    }
    std::nth_element(ms.begin(), ms.begin() + kTimedPasses / 2, ms.end());
    result.runs = true;
    result.detail =
        fmt::format("runs as {}, forward median {:.1f} ms ({} passes, one thread per CPU)",
                    detector.backend().name, ms[kTimedPasses / 2], kTimedPasses);
  } catch (const InputError& e) {
    result.detail = e.what();
  }
  return result;
}

void check_engines(ModelCheck& check) {
  const BackendCapabilities here = probe_backend_capabilities();
  check.engines.push_back(run_engine(check, BackendRequest::cpu));
  if (!here.xnnpack_built) {
    check.engines.push_back({"xnnpack", false, "not in this build (libxnnpack-dev, libonnx-dev)"});
  } else if (!xnnpack_runs_here()) {
    check.engines.push_back({"xnnpack", false, "XNNPACK does not initialize on this processor"});
  } else {
    check.engines.push_back(run_engine(check, BackendRequest::xnnpack));
  }
  if (!here.xnnpack_built || !xnnpack_runs_here()) {
    check.int8 = {"xnnpack-int8", false, "no XNNPACK engine here (above)"};
  } else {
    check.int8 = run_engine(check, BackendRequest::xnnpack_int8);
  }
  if (here.opencv_has_cuda && here.cuda_devices > 0) {
    check.engines.push_back(run_engine(check, BackendRequest::cuda));
  } else {
    check.engines.push_back(
        {"cuda", false,
         here.opencv_has_cuda ? "no CUDA device here" : "this OpenCV has no CUDA DNN backend"});
  }
  const bool any = std::any_of(check.engines.begin(), check.engines.end(),
                               [](const EngineCheck& e) { return e.runs; });
  if (!any) check.problems.push_back("engines: none of this build's engines runs the model");
}

}  // namespace

bool ModelCheck::usable() const {
  return problems.empty();
}

ModelCheck check_model(const ModelCheckConfig& config) {
  ModelCheck check;
  check.model = config.model_path;
  check.anchors_file =
      config.anchors_path.empty() ? default_anchors_path(config.model_path) : config.anchors_path;
  check.int8_ranges = config.int8_ranges.empty() ? default_activation_ranges_path(config.model_path)
                                                 : config.int8_ranges;
  // A path that is no model file at all (missing, a folder, a FIFO, too large) ends the check.
  open_model_file(check.model, kMaxModelBytes, "model");
  check.model_bytes = std::filesystem::file_size(check.model);
  check.description = read_model_description(check.model);
  try {
    const LabelTable labels = check.description.labels.empty()
                                  ? LabelTable::coco()
                                  : LabelTable::from_file(check.description.labels);
    check.labels = labels.source();
    check.label_columns = labels.columns();
  } catch (const InputError& e) {
    check.problems.push_back(std::string("labels: ") + e.what());
  }
  check.checksums = checksum_state(check);
  inspect_outputs(check);
  check_anchors(check);
  // Only a model whose interface fits is run on the engines: their errors would repeat the above.
  if (check.problems.empty()) check_engines(check);
  return check;
}

std::string format_model_check(const ModelCheck& check) {
  std::ostringstream out;
  const auto line = [&](const char* key, const std::string& value) {
    out << fmt::format("{:<10} {}\n", key, value);
  };
  line("model", fmt::format("{} ({:.1f} MB)", check.model.string(),
                            static_cast<double>(check.model_bytes) / 1e6));
  const ModelDescription& described = check.description;
  line("described", described.file.empty()
                        ? "no " + description_path_of(check.model).filename().string() +
                              " beside the model, none inside it: the bundled contract"
                        : described_by(described));
  line("checksums", check.checksums);
  line("input", fmt::format("fed N x 3 x {0} x {0} floats, {1} planes, (value - {2:g}) * {3:g}",
                            described.input_size, kColourOrderNames.name(described.colour),
                            described.mean, described.scale));
  std::vector<std::string> outputs;
  for (const auto& o : check.outputs) outputs.push_back(o.name + " " + shape_text(o.shape));
  line("outputs", outputs.empty() ? std::string("(none computed)")
                                  : fmt::format("{}", fmt::join(outputs, ", ")));
  if (check.anchors_in_model > 0) {
    line("layout", described.layout == OutputLayout::deltas
                       ? "deltas: box codes + class logits, decoded against an anchors file"
                       : "decoded: corner boxes in 0..1 + class probabilities");
    line("batch", check.batch_dimension ? "yes: N images in one pass (max_batch above 1 works)"
                                        : "no: one image per pass (max_batch must stay 1)");
  }
  if (check.anchors_in_file > 0) {
    line("anchors", fmt::format("{}: {} rows", check.anchors_file.string(), check.anchors_in_file));
  }
  if (check.class_columns > 0) {
    line("classes", fmt::format("{} columns, the first the background (labels: {})",
                                check.class_columns, check.labels));
  }
  for (const auto& engine : check.engines) {
    line("engine", engine.engine + ": " + (engine.runs ? engine.detail : "no: " + engine.detail));
  }
  if (!check.int8.engine.empty()) {
    line("int8",
         fmt::format("xnnpack-int8 with ranges {}: {}", check.int8_ranges.string(),
                     check.int8.runs ? "yes, " + check.int8.detail : "no: " + check.int8.detail));
  }
  for (const auto& problem : check.problems) line("problem", problem);
  line("verdict", check.usable()
                      ? "usable by rtmot run"
                      : fmt::format("not usable ({} problem(s) above)", check.problems.size()));
  return out.str();
}

}  // namespace rtmot::detector
