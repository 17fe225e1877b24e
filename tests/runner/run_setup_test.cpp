// The run setup (runner/run_detector.cpp) decides the detector's thread count in one place; the
// detector it builds must run with that count, since XNNPACK's pool and backend auto's choice
// depend on it (issue 32, class 6: it was handed 0, "every core", after the count was decided).
#include "runner/run_setup.hpp"

#include <gtest/gtest.h>

#include <string>

#include "detector/ssd_detector.hpp"
#include "detector/xnnpack_network.hpp"
#include "shared_data.hpp"

namespace rtmot::runner {
namespace {

RunConfig detector_config(detector::BackendRequest backend, int threads) {
  RunConfig config;
  config.detector.model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx").string();
  config.detector.backend = backend;
  config.detector.threads = threads;
  return config;
}

bool xnnpack_here() {
  return detector::xnnpack_built() && detector::xnnpack_runs_here();
}

TEST(RunSetupDetector, XnnpackRunsOnTheDecidedThreadCount) {
  if (!xnnpack_here()) GTEST_SKIP() << "no XNNPACK backend here";
  const auto one = make_detector(detector_config(detector::BackendRequest::xnnpack, 1));
  EXPECT_NE(one->describe().find(", 1 thread(s)]"), std::string::npos) << one->describe();
}

// Auto measures both CPU engines at start on the count decided, and says so.
TEST(RunSetupDetector, AutoMeasuresOnTheDecidedThreadCount) {
  if (!xnnpack_here()) GTEST_SKIP() << "no XNNPACK backend here";
  const auto caps = detector::probe_backend_capabilities();
  if (caps.opencv_has_cuda && caps.cuda_devices > 0) GTEST_SKIP() << "CUDA here: auto picks it";
  const auto built = make_detector(detector_config(detector::BackendRequest::automatic, 1));
  const auto* ssd = dynamic_cast<const detector::SsdDetector*>(built.get());
  ASSERT_NE(ssd, nullptr);
  const std::string& reason = ssd->backend().reason;
  EXPECT_NE(reason.find("measured at start on 1 thread(s)"), std::string::npos) << reason;
  EXPECT_NE(reason.find("xnnpack "), std::string::npos) << reason;
  EXPECT_NE(reason.find("OpenCV cpu "), std::string::npos) << reason;
  // The engine kept is the one the line names as faster.
  const bool xnnpack = ssd->backend().engine == detector::Engine::xnnpack;
  EXPECT_NE(reason.find(xnnpack ? ": xnnpack is faster" : ": OpenCV cpu is faster"),
            std::string::npos)
      << reason;
  EXPECT_EQ(ssd->backend().name, xnnpack ? "xnnpack" : "cpu");
}

}  // namespace
}  // namespace rtmot::runner
