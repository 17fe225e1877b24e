// A missing, truncated or corrupt model (or anchors file) is an InputError with ExitCode::bad_model
// that names the file; a backend or class that cannot be had is a usage error.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/ssd_detector.hpp"
#include "shared_data.hpp"

namespace rtmot::detector {
namespace {

const std::filesystem::path kModelName = "ssdlite_mobilenet_v2_coco.onnx";
const std::filesystem::path kAnchorsName = "ssdlite_mobilenet_v2_coco.anchors.csv";

class SsdModelErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    real_model_ = test::source_path("models") / kModelName;
    if (!std::filesystem::exists(real_model_)) {
      FAIL() << "missing model " << real_model_ << ": run scripts/fetch_model.sh";
    }
    dir_ = std::filesystem::temp_directory_path() /
           ("rtmot_detector_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    std::filesystem::copy_file(default_anchors_path(real_model_), dir_ / kAnchorsName);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  void write(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  }
  std::string real_model_bytes() const {
    std::ifstream in(real_model_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  SsdConfig config_for(const std::filesystem::path& model) const {
    SsdConfig config;
    config.model_path = model;
    config.backend = BackendRequest::cpu;
    return config;
  }
  static void expect_model_error(const SsdConfig& config, const std::filesystem::path& named) {
    try {
      SsdDetector detector(config);
      ADD_FAILURE() << "no error for " << named;
    } catch (const InputError& e) {
      EXPECT_EQ(e.exit_code(), ExitCode::bad_model) << e.what();
      EXPECT_EQ(e.file(), named.string()) << e.what();
      // One line (issue 32: OpenCV's message spanned three, its source file and line first).
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find(".cpp:"), std::string::npos) << e.what();
    }
  }

  std::filesystem::path real_model_;
  std::filesystem::path dir_;
};

TEST_F(SsdModelErrors, MissingModelSaysHowToGetIt) {
  const auto config = config_for(dir_ / kModelName);
  try {
    SsdDetector detector(config);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    EXPECT_EQ(e.file(), config.model_path.string());
    EXPECT_NE(std::string(e.what()).find("scripts/fetch_model.sh"), std::string::npos) << e.what();
  }
}

TEST_F(SsdModelErrors, TruncatedModel) {
  const std::string bytes = real_model_bytes();
  write(dir_ / kModelName, bytes.substr(0, bytes.size() / 2));
  expect_model_error(config_for(dir_ / kModelName), dir_ / kModelName);
}

TEST_F(SsdModelErrors, CorruptModel) {
  write(dir_ / kModelName, std::string(4096, '\x7f') + "not a protobuf");
  expect_model_error(config_for(dir_ / kModelName), dir_ / kModelName);
}

TEST_F(SsdModelErrors, MissingAnchors) {
  std::filesystem::copy_file(real_model_, dir_ / kModelName);
  std::filesystem::remove(dir_ / kAnchorsName);
  expect_model_error(config_for(dir_ / kModelName), dir_ / kAnchorsName);
}

TEST_F(SsdModelErrors, MalformedAnchorsNameTheLine) {
  std::filesystem::copy_file(real_model_, dir_ / kModelName);
  write(dir_ / kAnchorsName, "# comment\n0.5,0.5,0.1,0.1\n0.5,zero,0.1,0.1\n");
  try {
    SsdDetector detector(config_for(dir_ / kModelName));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.field(), "xcenter");
  }
}

TEST_F(SsdModelErrors, AnchorsThatDoNotFitTheModel) {
  std::filesystem::copy_file(real_model_, dir_ / kModelName);
  write(dir_ / kAnchorsName, "0.5,0.5,0.1,0.1\n0.2,0.2,0.1,0.1\n");
  expect_model_error(config_for(dir_ / kModelName), dir_ / kModelName);
}

TEST_F(SsdModelErrors, ClassOutsideCocoIsAUsageError) {
  std::filesystem::copy_file(real_model_, dir_ / kModelName);
  auto config = config_for(dir_ / kModelName);
  config.classes = {1, 91};
  try {
    SsdDetector detector(config);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::usage);
    EXPECT_EQ(e.field(), "classes");
  }
}

TEST(DnnBackend, AutomaticPicksCudaOnlyWhenUsable) {
  const BackendCapabilities none{};
  EXPECT_EQ(choose_backend(BackendRequest::automatic, Fp16Request::automatic, none).name, "cpu");
  const BackendCapabilities built_no_device{true, 0, false};
  const auto cpu =
      choose_backend(BackendRequest::automatic, Fp16Request::automatic, built_no_device);
  EXPECT_EQ(cpu.name, "cpu");
  EXPECT_NE(cpu.reason.find("no CUDA device"), std::string::npos) << cpu.reason;
  const BackendCapabilities jetson{true, 1, true};
  EXPECT_EQ(choose_backend(BackendRequest::automatic, Fp16Request::automatic, jetson).name,
            "cuda-fp16");
  EXPECT_EQ(choose_backend(BackendRequest::automatic, Fp16Request::off, jetson).name, "cuda");
  EXPECT_EQ(choose_backend(BackendRequest::cpu, Fp16Request::automatic, jetson).name, "cpu");
  const BackendCapabilities discrete{true, 1, false};
  EXPECT_EQ(choose_backend(BackendRequest::automatic, Fp16Request::automatic, discrete).name,
            "cuda");
  EXPECT_EQ(choose_backend(BackendRequest::cuda, Fp16Request::on, discrete).name, "cuda-fp16");
}

TEST(DnnBackend, AutomaticMeasuresBothCpuEnginesWithoutCuda) {
  BackendCapabilities xnnpack{};
  xnnpack.xnnpack_built = true;
  // Which CPU engine is faster depends on the machine and its load: the detector measures both.
  const auto automatic = choose_backend(BackendRequest::automatic, Fp16Request::automatic, xnnpack);
  EXPECT_TRUE(automatic.measure);
  EXPECT_EQ(automatic.engine, Engine::xnnpack);
  EXPECT_NE(automatic.reason.find("without the CUDA DNN backend"), std::string::npos)
      << automatic.reason;
  // Asked for: no measurement; without XNNPACK auto is OpenCV, unmeasured.
  const auto asked = choose_backend(BackendRequest::xnnpack, Fp16Request::automatic, xnnpack);
  EXPECT_EQ(asked.engine, Engine::xnnpack);
  EXPECT_FALSE(asked.measure);
  EXPECT_FALSE(choose_backend(BackendRequest::cpu, Fp16Request::automatic, xnnpack).measure);
  const auto without =
      choose_backend(BackendRequest::automatic, Fp16Request::automatic, BackendCapabilities{});
  EXPECT_EQ(without.engine, Engine::opencv);
  EXPECT_FALSE(without.measure);
  // CUDA still first for auto.
  xnnpack.opencv_has_cuda = true;
  xnnpack.cuda_devices = 1;
  EXPECT_EQ(choose_backend(BackendRequest::automatic, Fp16Request::off, xnnpack).name, "cuda");
  // Not built: refused when asked for, with the way to get it.
  try {
    choose_backend(BackendRequest::xnnpack, Fp16Request::automatic, BackendCapabilities{});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::usage);
    EXPECT_NE(std::string(e.what()).find("libxnnpack-dev"), std::string::npos) << e.what();
  }
  EXPECT_EQ(kBackendNames.parse("xnnpack"), BackendRequest::xnnpack);
}

// int8 only when asked (its numbers differ from fp32's): auto never picks it.
TEST(DnnBackend, Int8IsXnnpackInInt8AndOnlyWhenAsked) {
  BackendCapabilities xnnpack{};
  xnnpack.xnnpack_built = true;
  EXPECT_EQ(kBackendNames.parse("xnnpack-int8"), BackendRequest::xnnpack_int8);
  const auto int8 = choose_backend(BackendRequest::xnnpack_int8, Fp16Request::automatic, xnnpack);
  EXPECT_EQ(int8.engine, Engine::xnnpack);
  EXPECT_TRUE(int8.int8);
  EXPECT_FALSE(int8.measure);
  EXPECT_EQ(int8.name, "xnnpack-int8");
  EXPECT_FALSE(choose_backend(BackendRequest::automatic, Fp16Request::automatic, xnnpack).int8);
  EXPECT_FALSE(choose_backend(BackendRequest::xnnpack, Fp16Request::automatic, xnnpack).int8);
  try {
    choose_backend(BackendRequest::xnnpack_int8, Fp16Request::automatic, BackendCapabilities{});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::usage);
    EXPECT_EQ(e.field(), "backend");
    EXPECT_NE(std::string(e.what()).find("xnnpack-int8 was requested"), std::string::npos)
        << e.what();
  }
}

TEST(DnnBackend, ForcingWhatCannotBeHadIsAClearError) {
  const BackendCapabilities none{};
  try {
    choose_backend(BackendRequest::cuda, Fp16Request::automatic, none);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::usage);
    EXPECT_NE(std::string(e.what()).find("without the CUDA DNN backend"), std::string::npos);
  }
  EXPECT_THROW(choose_backend(BackendRequest::cpu, Fp16Request::on, none), InputError);
}

// The real detector asked for CUDA: on a build or machine without it (Debian's OpenCV, CI) a usage
// error at start-up that says why and where to go; where CUDA is there (the GPU machine) it runs on
// it and says so.
TEST_F(SsdModelErrors, CudaRequestedWhereItCannotBeHad) {
  std::filesystem::copy_file(real_model_, dir_ / kModelName);
  auto config = config_for(dir_ / kModelName);
  config.backend = BackendRequest::cuda;
  const auto caps = probe_backend_capabilities();
  if (caps.opencv_has_cuda && caps.cuda_devices > 0) {
    SsdDetector detector(config);
    EXPECT_EQ(detector.backend().name, "cuda") << detector.describe();
    EXPECT_NE(detector.describe().find("cuda requested"), std::string::npos);
    return;
  }
  try {
    SsdDetector detector(config);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::usage);
    EXPECT_EQ(e.field(), "backend");
    EXPECT_NE(std::string(e.what()).find("docs/gpu.md"), std::string::npos) << e.what();
  }
}

TEST(DnnBackend, ParsesConfigWords) {
  EXPECT_EQ(kBackendNames.parse("cuda"), BackendRequest::cuda);
  EXPECT_EQ(kBackendNames.parse("gpu"), std::nullopt);
  EXPECT_EQ(parse_fp16_request("auto"), Fp16Request::automatic);
  EXPECT_EQ(parse_fp16_request("false"), Fp16Request::off);
  EXPECT_EQ(parse_fp16_request("maybe"), std::nullopt);
}

// A forward pass that fails once the detector runs (provoked by the test hook
// RTMOT_FAULT_FORWARD_AFTER, detector/forward_fault.hpp): the first N frames are detected, then an
// InputError with exit code bad_model names the backend; on CUDA (the GPU machine runs this on
// cuda) it names the way out, `backend: cpu`.
TEST_F(SsdModelErrors, AForwardThatFailsAtRunTimeNamesTheBackendAndTheWayOut) {
  const auto caps = probe_backend_capabilities();
  const bool cuda = caps.opencv_has_cuda && caps.cuda_devices > 0;
  auto config = config_for(real_model_);
  config.backend = cuda ? BackendRequest::cuda : BackendRequest::cpu;
  ::setenv("RTMOT_FAULT_FORWARD_AFTER", "2", 1);
  SsdDetector detector(config);  // its start-up passes do not count
  ::unsetenv("RTMOT_FAULT_FORWARD_AFTER");
  const cv::Mat image(240, 320, CV_8UC3, cv::Scalar(90, 120, 150));
  std::vector<tracker::Detection> boxes;
  detector.detect(image, 1, boxes);
  detector.detect(image, 2, boxes);
  try {
    detector.detect(image, 3, boxes);
    FAIL() << "the third forward pass did not fail";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    const std::string what = e.what();
    EXPECT_NE(what.find("the forward pass failed on " + detector.backend().name + " at run time"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("RTMOT_FAULT_FORWARD_AFTER=2"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    if (cuda) {
      EXPECT_NE(what.find("backend: cpu"), std::string::npos) << what;
    }
  }
}

TEST(DnnBackend, ARunTimeFailureOnCudaSaysBackendCpu) {
  for (const char* name : {"cuda", "cuda-fp16"}) {
    const BackendChoice cuda{Engine::opencv, cv::dnn::DNN_BACKEND_CUDA, cv::dnn::DNN_TARGET_CUDA,
                             name, "cuda requested"};
    const InputError error = forward_failure(cuda, "cudaErrorLaunchFailure: unspecified");
    EXPECT_EQ(error.exit_code(), ExitCode::bad_model);
    EXPECT_EQ(std::string(error.what()),
              std::string("detector: the forward pass failed on ") + name +
                  " at run time (cudaErrorLaunchFailure: unspecified): set 'backend: cpu' in the "
                  "detector config to run without the GPU");
  }
  const BackendChoice cpu{Engine::opencv, cv::dnn::DNN_BACKEND_OPENCV, cv::dnn::DNN_TARGET_CPU,
                          "cpu", "cpu requested"};
  EXPECT_EQ(std::string(forward_failure(cpu, "x").what()).find("backend: cpu"), std::string::npos);
}

// The hook refuses what is not a count rather than never firing.
TEST_F(SsdModelErrors, AFaultHookThatIsNotACountIsAUsageError) {
  ::setenv("RTMOT_FAULT_FORWARD_AFTER", "soon", 1);
  try {
    SsdDetector detector(config_for(real_model_));
    ::unsetenv("RTMOT_FAULT_FORWARD_AFTER");
    FAIL() << "no error";
  } catch (const InputError& e) {
    ::unsetenv("RTMOT_FAULT_FORWARD_AFTER");
    EXPECT_EQ(e.exit_code(), ExitCode::usage);
    EXPECT_NE(std::string(e.what()).find("RTMOT_FAULT_FORWARD_AFTER"), std::string::npos);
  }
}

}  // namespace
}  // namespace rtmot::detector
