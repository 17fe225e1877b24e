// Where a batch-1 forward's time goes (docs/gpu.md §3), run by scripts/opencv/gpu_machine.sh: the
// wall time of setInput + forward against the host time OpenCV spends in each layer
// (Net::getPerfProfile: on CUDA it times each layer's launch on the host, the kernels run
// asynchronously), summed per layer type. A tool of the GPU run, not of the product.
//
//   forward_profile MODEL.onnx cpu|cuda|cuda-fp16 [ITERATIONS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <string>
#include <vector>

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: forward_profile MODEL.onnx cpu|cuda|cuda-fp16 [ITERATIONS]\n");
    return 2;
  }
  const std::string backend = argv[2];
  const int iterations = argc > 3 ? std::stoi(argv[3]) : 300;
  cv::dnn::Net net = cv::dnn::readNetFromONNX(argv[1]);
  if (backend == "cpu") {
    net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
    net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  } else if (backend == "cuda" || backend == "cuda-fp16") {
    net.setPreferableBackend(cv::dnn::DNN_BACKEND_CUDA);
    net.setPreferableTarget(backend == "cuda" ? cv::dnn::DNN_TARGET_CUDA
                                              : cv::dnn::DNN_TARGET_CUDA_FP16);
  } else {
    std::fprintf(stderr, "forward_profile: unknown backend '%s'\n", backend.c_str());
    return 2;
  }
  // A real-looking input (not zeros): uniform in the model's [-1, 1] range.
  cv::Mat blob(std::vector<int>{1, 3, 300, 300}, CV_32F);
  cv::randu(blob, -1.0F, 1.0F);
  const auto outputs = net.getUnconnectedOutLayersNames();
  std::vector<cv::Mat> results;
  for (int i = 0; i < 20; ++i) {
    net.setInput(blob);
    net.forward(results, outputs);
  }
  const auto names = net.getLayerNames();
  std::vector<double> wall_ms;
  std::vector<double> layers_ms;
  std::map<std::string, std::pair<double, int>> by_type;  // summed ms over iterations, layer count
  const double tick_ms = 1000.0 / cv::getTickFrequency();
  for (int i = 0; i < iterations; ++i) {
    const auto start = std::chrono::steady_clock::now();
    net.setInput(blob);
    net.forward(results, outputs);
    wall_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    std::vector<double> timings;
    layers_ms.push_back(static_cast<double>(net.getPerfProfile(timings)) * tick_ms);
    for (std::size_t l = 0; l < timings.size() && l < names.size(); ++l) {
      if (timings[l] <= 0) continue;  // fused into another layer, or skipped
      const auto layer = net.getLayer(names[l]);
      auto& entry = by_type[layer->type];
      entry.first += timings[l] * tick_ms;
      if (i == 0) ++entry.second;
    }
  }
  std::printf("%s: %zu layers, %d iterations\n", backend.c_str(), names.size(), iterations);
  std::printf("forward wall (setInput + forward) min %.3f / median %.3f ms\n",
              *std::min_element(wall_ms.begin(), wall_ms.end()), median(wall_ms));
  std::printf("sum of per-layer host time (getPerfProfile) median %.3f ms\n", median(layers_ms));
  std::vector<std::pair<std::string, std::pair<double, int>>> rows(by_type.begin(), by_type.end());
  std::sort(rows.begin(), rows.end(),
            [](const auto& a, const auto& b) { return a.second.first > b.second.first; });
  std::printf("%-22s %7s %12s %14s\n", "layer type", "layers", "ms/forward", "us/layer");
  for (const auto& [type, entry] : rows) {
    const double per_forward = entry.first / iterations;
    std::printf("%-22s %7d %12.3f %14.1f\n", type.c_str(), entry.second, per_forward,
                entry.second > 0 ? 1000.0 * per_forward / entry.second : 0.0);
  }
  return 0;
}
