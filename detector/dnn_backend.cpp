#include "detector/dnn_backend.hpp"

#include <algorithm>
#include <opencv2/core/cuda.hpp>
#include <opencv2/dnn.hpp>
#include <utility>

#include "common/input_error.hpp"
#include "detector/xnnpack_network.hpp"

namespace rtmot::detector {

std::optional<Fp16Request> parse_fp16_request(const std::string& text) {
  if (const auto named = kFp16Names.parse(text)) return named;
  if (text == "true") return Fp16Request::on;
  if (text == "false") return Fp16Request::off;
  return std::nullopt;
}

BackendCapabilities probe_backend_capabilities() {
  BackendCapabilities caps;
  const auto available = cv::dnn::getAvailableBackends();
  caps.opencv_has_cuda = std::any_of(available.begin(), available.end(), [](const auto& pair) {
    return pair.first == cv::dnn::DNN_BACKEND_CUDA;
  });
  caps.cuda_devices = cv::cuda::getCudaEnabledDeviceCount();
  if (caps.cuda_devices > 0) caps.integrated_gpu = cv::cuda::DeviceInfo(0).integrated();
  caps.xnnpack_built = xnnpack_built();
  return caps;
}

BackendChoice choose_backend(BackendRequest backend, Fp16Request fp16,
                             const BackendCapabilities& caps) {
  const bool cuda_possible = caps.opencv_has_cuda && caps.cuda_devices > 0;
  const std::string why_not_cuda = !caps.opencv_has_cuda
                                       ? "this OpenCV was built without the CUDA DNN backend"
                                       : "no CUDA device was found";
  if (backend == BackendRequest::cuda && !cuda_possible) {
    // Named as the configuration's detector section: the message then reads "detector: field
    // 'backend': ...", with the way out.
    throw InputError("detector", 0, "backend",
                     "cuda was requested but " + why_not_cuda +
                         " (build OpenCV with scripts/build_opencv.sh --cuda: docs/gpu.md)",
                     ExitCode::usage);
  }
  const bool xnnpack_asked =
      backend == BackendRequest::xnnpack || backend == BackendRequest::xnnpack_int8;
  if (xnnpack_asked && !caps.xnnpack_built) {
    throw InputError("detector", 0, "backend",
                     std::string(kBackendNames.name(backend)) +
                         " was requested but this build has no XNNPACK backend (install "
                         "libxnnpack-dev and libonnx-dev, scripts/install_deps.sh, and rebuild: "
                         "docs/cpu-detector.md)",
                     ExitCode::usage);
  }
  const bool use_cuda =
      backend == BackendRequest::cuda || (backend == BackendRequest::automatic && cuda_possible);
  if (!use_cuda) {
    if (fp16 == Fp16Request::on) {
      throw InputError("detector", 0, "fp16",
                       "fp16 needs the cuda backend; the detector runs on the cpu",
                       ExitCode::usage);
    }
    if (backend == BackendRequest::xnnpack) {
      return {Engine::xnnpack, 0, 0, "xnnpack", "xnnpack requested"};
    }
    if (backend == BackendRequest::xnnpack_int8) {
      return {Engine::xnnpack, 0, 0, "xnnpack-int8", "xnnpack-int8 requested", false, true};
    }
    if (backend == BackendRequest::automatic && caps.xnnpack_built) {
      return {Engine::xnnpack,
              0,
              0,
              "xnnpack",
              why_not_cuda + "; xnnpack and OpenCV's cpu path to be measured at start",
              true};
    }
    const std::string reason = backend == BackendRequest::cpu
                                   ? "cpu requested"
                                   : why_not_cuda + "; no xnnpack in this build";
    return {Engine::opencv, cv::dnn::DNN_BACKEND_OPENCV, cv::dnn::DNN_TARGET_CPU, "cpu", reason};
  }
  const std::string origin = backend == BackendRequest::cuda ? "cuda requested" : "cuda available";
  const bool half =
      fp16 == Fp16Request::on || (fp16 == Fp16Request::automatic && caps.integrated_gpu);
  const std::string fp16_reason = fp16 == Fp16Request::on    ? "fp16 requested"
                                  : fp16 == Fp16Request::off ? "fp16 off by request"
                                  : half                     ? "fp16 on an integrated (Jetson) GPU"
                                                             : "fp32 on a discrete GPU";
  return {Engine::opencv, cv::dnn::DNN_BACKEND_CUDA,
          half ? cv::dnn::DNN_TARGET_CUDA_FP16 : cv::dnn::DNN_TARGET_CUDA,
          half ? "cuda-fp16" : "cuda", origin + ", " + fp16_reason};
}

}  // namespace rtmot::detector
