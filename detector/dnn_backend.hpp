#pragma once
// Which engine (OpenCV DNN backend/target, or XNNPACK) runs the SSD, decided once at start-up.
#include <optional>
#include <string>
#include <string_view>

#include "tracker/enum_names.hpp"

namespace rtmot::detector {

enum class BackendRequest { automatic, cpu, cuda, xnnpack, xnnpack_int8 };
/// The one table of backend names, for parsing, messages and docs/config.md.
inline constexpr auto kBackendNames = tracker::make_enum_names<BackendRequest>(
    std::pair{BackendRequest::automatic, std::string_view("auto")},
    std::pair{BackendRequest::cpu, std::string_view("cpu")},
    std::pair{BackendRequest::cuda, std::string_view("cuda")},
    std::pair{BackendRequest::xnnpack, std::string_view("xnnpack")},
    std::pair{BackendRequest::xnnpack_int8, std::string_view("xnnpack-int8")});

enum class Fp16Request { automatic, on, off };
/// The one table of fp16 names, for parsing, messages and docs/config.md.
inline constexpr auto kFp16Names = tracker::make_enum_names<Fp16Request>(
    std::pair{Fp16Request::automatic, std::string_view("auto")},
    std::pair{Fp16Request::on, std::string_view("on")},
    std::pair{Fp16Request::off, std::string_view("off")});

/// A name of kFp16Names -> request; YAML's booleans true/false also read as on/off (`fp16: true`
/// is what a YAML writer types). nullopt otherwise.
std::optional<Fp16Request> parse_fp16_request(const std::string& text);

/// What runs the forward pass: OpenCV DNN (backend/target below) or the XNNPACK subgraph.
enum class Engine { opencv, xnnpack };

struct BackendChoice {
  Engine engine{Engine::opencv};
  int backend{0};      // cv::dnn::Backend
  int target{0};       // cv::dnn::Target
  std::string name;    // "cpu", "cuda", "cuda-fp16", "xnnpack", "xnnpack-int8"
  std::string reason;  // why, for the log
  /// Backend auto on the CPU with XNNPACK built: which CPU engine is faster depends on the
  /// processor and on what else runs on its cores, so SsdDetector times both at start (a few
  /// passes each) and keeps the faster; engine is xnnpack until then.
  bool measure{false};
  /// XNNPACK's int8 engine on calibrated activation ranges (only when asked: its numbers differ
  /// from fp32's, within the tolerance docs/cpu-detector.md documents, so auto never picks it).
  bool int8{false};
};

/// What this machine offers that the SSD can use.
struct BackendCapabilities {
  bool opencv_has_cuda{false};  // cv::dnn::getAvailableBackends() lists DNN_BACKEND_CUDA
  int cuda_devices{0};          // cv::cuda::getCudaEnabledDeviceCount()
  bool integrated_gpu{false};   // device 0 shares memory with the CPU: a Jetson board
  bool xnnpack_built{false};    // this build has the XNNPACK backend
};

BackendCapabilities probe_backend_capabilities();

/// CUDA when asked or (automatic) when available; else (automatic) both CPU engines measured at
/// start when XNNPACK is built in (`measure`), else OpenCV's CPU path. FP16 on CUDA when asked or
/// (automatic) on Jetson boards, where it roughly doubles throughput at no measurable accuracy
/// cost; discrete GPUs without tensor-core paths in OpenCV gain little. Throws rtmot::InputError
/// (ExitCode::usage) when CUDA or XNNPACK is forced but impossible, or FP16 is forced on the CPU.
BackendChoice choose_backend(BackendRequest backend, Fp16Request fp16,
                             const BackendCapabilities& capabilities);

}  // namespace rtmot::detector
