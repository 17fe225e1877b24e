// The int8 engine (backend xnnpack-int8, docs/cpu-detector.md "INT8"): its detections against the
// fp32 engine's on the same frames, within the tolerance measured and documented there; the
// committed calibration reproduced from its sample frames; and the ranges file's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/activation_ranges.hpp"
#include "detector/int8_calibration.hpp"
#include "detector/model_checksum.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/xnnpack_network.hpp"
#include "int8_match.hpp"
#include "shared_data.hpp"
#include "vtest_frames.hpp"

namespace rtmot::detector {
namespace {

namespace fs = std::filesystem;

fs::path model_path() {
  return test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
}
fs::path ranges_path() {
  return test::source_path("configs/int8/ssdlite_mobilenet_v2_coco.ranges");
}

#define RTMOT_REQUIRE_XNNPACK()                                                           \
  do {                                                                                    \
    if (!xnnpack_built()) GTEST_SKIP() << "this build has no XNNPACK backend";            \
    if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this CPU";  \
    if (!fs::exists(model_path())) FAIL() << "missing model: run scripts/fetch_model.sh"; \
  } while (false)

TEST(XnnpackInt8, DetectionsMatchFp32WithinTheDocumentedTolerance) {
  RTMOT_REQUIRE_XNNPACK();
  std::set<int> numbers = test::reference_frame_numbers();
  // Under qemu two frames (each forward of both engines takes seconds there).
  if (test::under_emulation()) numbers = {*numbers.begin(), *std::next(numbers.begin())};
  const auto frames = test::vtest_frames(numbers);
  ASSERT_EQ(frames.size(), numbers.size());

  SsdConfig config;
  config.model_path = model_path();
  config.int8_ranges = ranges_path();
  config.score_threshold = test::kInt8Cut;
  config.classes = {};  // all
  config.plausible_shapes = false;
  config.threads = 1;
  config.backend = BackendRequest::xnnpack;
  SsdDetector fp32(config);
  config.backend = BackendRequest::xnnpack_int8;
  SsdDetector int8(config);
  EXPECT_NE(int8.describe().find("int8"), std::string::npos) << int8.describe();

  const test::Int8Match match = test::match_int8(fp32, int8, frames);
  ASSERT_GE(match.sure, 5 * static_cast<int>(frames.size()) / 2) << "too few detections to judge";
  ASSERT_FALSE(match.box_moves.empty());
  std::cout << "int8 vs fp32 over " << frames.size() << " frames: matched " << match.matched << "/"
            << match.sure << " detections of score >= " << test::kInt8Sure << "; box move median "
            << match.median_box() << " px, worst " << match.worst_box()
            << " px; score change median " << match.median_score() << ", worst "
            << match.worst_score() << "\n";
  EXPECT_GE(static_cast<double>(match.matched), test::kInt8MinMatchedShare * match.sure);
  EXPECT_LE(match.median_box(), test::kInt8MedianBoxPx);
  EXPECT_LE(match.median_score(), test::kInt8MedianScore);
  EXPECT_LE(match.worst_score(), test::kInt8WorstScore);
}

// The committed ranges are what scripts/calibrate_int8.sh computes from the model and its sample
// frames. Frames decoded otherwise (RTMOT_VTEST_FRAMES: FFmpeg's pixels) move ranges slightly.
TEST(XnnpackInt8, CommittedRangesReproduceFromTheSampleFrames) {
  RTMOT_REQUIRE_XNNPACK();
  if (test::under_emulation()) {
    GTEST_SKIP() << "16 fp32 forwards (minutes under qemu); the ranges are checked on x86-64";
  }
  const ActivationRanges committed = read_activation_ranges(ranges_path());
  EXPECT_EQ(committed.model_sha256, sha256_file_hex(model_path()))
      << ranges_path() << " belongs to another model: run scripts/calibrate_int8.sh";
  std::set<int> numbers;
  for (int i = 0; i < kCalibrationFrames; ++i) {
    numbers.insert(kCalibrationFirstFrame + i * kCalibrationFrameStep);
  }
  const auto decoded = test::vtest_frames(numbers);
  ASSERT_EQ(decoded.size(), numbers.size());
  std::vector<cv::Mat> frames;
  for (const auto& [number, image] : decoded) frames.push_back(image);
  SsdConfig config;
  config.model_path = model_path();
  const ActivationRanges computed = calibrate_activation_ranges(config, frames);
  EXPECT_EQ(computed.frames, committed.frames);
  ASSERT_EQ(computed.tensors.size(), committed.tensors.size());
  const float allowed = test::vtest_frames_decoded_as_reference() ? 0.05F : 0.001F;
  float worst = 0.F;
  for (const auto& [name, range] : committed.tensors) {
    const auto found = computed.tensors.find(name);
    ASSERT_NE(found, computed.tensors.end()) << name;
    const float width = std::max(range.max - range.min, 1e-6F);
    const float off =
        std::max(std::abs(found->second.min - range.min), std::abs(found->second.max - range.max)) /
        width;
    worst = std::max(worst, off);
    EXPECT_LE(off, allowed) << name << ": committed " << range.min << ".." << range.max
                            << ", computed " << found->second.min << ".." << found->second.max;
  }
  std::cout << computed.tensors.size() << " tensors, worst range change " << worst
            << " of the range's width\n";
}

class ActivationRangesFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rtmot-int8-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& text) const {
    const fs::path path = dir_ / "model.ranges";
    std::ofstream(path) << text;
    return path;
  }
  /// The error of reading `text`: file, line, field and message.
  InputError error_of(const std::string& text) const {
    try {
      read_activation_ranges(write(text));
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return InputError("", 0, "", "", ExitCode::bad_model);
  }
  fs::path dir_;
};

const std::string kSha(64, 'a');

TEST_F(ActivationRangesFile, ReadsBackWhatItWrites) {
  ActivationRanges ranges;
  ranges.model_sha256 = kSha;
  ranges.frames = 3;
  ranges.tensors["conv/Relu6"] = {0.F, 5.99999952F};
  ranges.tensors["head"] = {-14.7573242F, 5.32757902F};
  const ActivationRanges read = read_activation_ranges(write(activation_ranges_text(ranges)));
  EXPECT_EQ(read.model_sha256, kSha);
  EXPECT_EQ(read.frames, 3);
  ASSERT_EQ(read.tensors.size(), 2U);
  EXPECT_EQ(read.tensors.at("head").min, -14.7573242F);
  EXPECT_EQ(read.tensors.at("conv/Relu6").max, 5.99999952F);
}

TEST_F(ActivationRangesFile, DamageIsNamedByLineAndField) {
  const std::string head = "model_sha256 " + kSha + "\nframes 2\n";
  struct Bad {
    std::string text;
    int line;
    std::string field;
  };
  for (const Bad& bad : {
           Bad{head + "range a 0 1\nrange b 1 zero\n", 4, "b"},
           Bad{head + "range a 0 nan\n", 3, "a"},
           Bad{head + "range a 2 1\n", 3, "a"},
           Bad{head + "range a 0 1\nrange a 0 1\n", 4, "a"},
           Bad{head + "range a 0\n", 3, "range"},
           Bad{head + "scale a 0 1\n", 3, "scale"},
           Bad{"model_sha256 1234\n", 1, "model_sha256"},
           Bad{"frames 0\n", 1, "frames"},
           Bad{"frames 2\nrange a 0 1\n", 0, "model_sha256"},
           Bad{head, 0, "range"},
       }) {
    const InputError e = error_of(bad.text);
    EXPECT_EQ(e.file(), (dir_ / "model.ranges").string()) << bad.text;
    EXPECT_EQ(e.line(), bad.line) << bad.text << e.what();
    EXPECT_EQ(e.field(), bad.field) << bad.text << e.what();
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
  }
}

TEST_F(ActivationRangesFile, RangesOfAnotherModelAreRefused) {
  RTMOT_REQUIRE_XNNPACK();
  ActivationRanges ranges = read_activation_ranges(ranges_path());
  ranges.model_sha256 = kSha;
  SsdConfig config;
  config.model_path = model_path();
  config.int8_ranges = write(activation_ranges_text(ranges));
  config.backend = BackendRequest::xnnpack_int8;
  config.threads = 1;
  try {
    SsdDetector detector(config);
    ADD_FAILURE() << "ranges of another model accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), config.int8_ranges.string());
    EXPECT_EQ(e.field(), "model_sha256");
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    EXPECT_NE(std::string(e.what()).find("calibrate_int8.sh"), std::string::npos) << e.what();
  }
}

TEST_F(ActivationRangesFile, ATensorWithoutARangeIsNamed) {
  RTMOT_REQUIRE_XNNPACK();
  ActivationRanges ranges = read_activation_ranges(ranges_path());
  const std::string dropped = ranges.tensors.begin()->first;
  ranges.tensors.erase(ranges.tensors.begin());
  SsdConfig config;
  config.model_path = model_path();
  config.int8_ranges = write(activation_ranges_text(ranges));
  config.backend = BackendRequest::xnnpack_int8;
  config.threads = 1;
  try {
    SsdDetector detector(config);
    ADD_FAILURE() << "a missing range accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), config.int8_ranges.string());
    EXPECT_NE(std::string(e.what()).find(dropped), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
  }
}

}  // namespace
}  // namespace rtmot::detector
