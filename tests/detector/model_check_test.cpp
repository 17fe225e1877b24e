// `rtmot model check`'s findings (detector/model_check.hpp) on the bundled model and on model
// folders where one thing does not fit the contract: each problem names its field, and a model
// that fits runs on every engine this build has.
#include "detector/model_check.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "detector/xnnpack_network.hpp"
#include "shared_data.hpp"

namespace rtmot::detector {
namespace {

namespace fs = std::filesystem;

class ModelCheckTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
    anchors_ = test::source_path("models/ssdlite_mobilenet_v2_coco.anchors.csv");
    if (!fs::exists(model_)) FAIL() << "missing model " << model_ << ": run scripts/fetch_model.sh";
    dir_ = fs::temp_directory_path() /
           ("rtmot-model-check-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static bool any_problem_with(const ModelCheck& check, const std::string& text) {
    for (const auto& problem : check.problems) {
      if (problem.find(text) != std::string::npos) return true;
    }
    return false;
  }

  fs::path model_;
  fs::path anchors_;
  fs::path dir_;
};

TEST_F(ModelCheckTest, TheBundledModelFitsAndRunsOnEveryEngineOfThisBuild) {
  const ModelCheck check = check_model({model_, {}, {}});
  const std::string report = format_model_check(check);
  std::cout << report;
  EXPECT_TRUE(check.problems.empty()) << report;
  EXPECT_TRUE(check.usable());
  ASSERT_EQ(check.outputs.size(), 2U);
  EXPECT_EQ(check.anchors_in_model, 1917);
  EXPECT_EQ(check.anchors_in_file, 1917);
  EXPECT_EQ(check.class_columns, 91);
  EXPECT_TRUE(check.batch_dimension);
  EXPECT_EQ(check.anchors_file, anchors_);
  EXPECT_EQ(check.checksums.rfind("verified: 2 file(s)", 0), 0U) << check.checksums;
  ASSERT_EQ(check.engines.size(), 3U);  // cpu, xnnpack, cuda: each runs or says why not
  EXPECT_EQ(check.engines[0].engine, "cpu");
  EXPECT_TRUE(check.engines[0].runs) << check.engines[0].detail;
  EXPECT_EQ(check.engines[1].engine, "xnnpack");
  EXPECT_EQ(check.engines[1].runs, xnnpack_built() && xnnpack_runs_here())
      << check.engines[1].detail;
  EXPECT_NE(report.find("outputs    box_encodings [1, 1917, 4], class_logits [1, 1917, 91]\n"),
            std::string::npos);
  EXPECT_NE(report.find("verdict    usable by rtmot run\n"), std::string::npos);
}

// The int8 line: backend xnnpack-int8 with the ranges file it would read (the committed one
// here), or why not (a file that is not there: named, with the way to make it). It does not
// decide the verdict: `auto` never chooses int8.
TEST_F(ModelCheckTest, TheInt8LineNamesItsRangesFile) {
  const fs::path ranges = test::source_path("configs/int8/ssdlite_mobilenet_v2_coco.ranges");
  const ModelCheck check = check_model({model_, {}, ranges});
  const std::string report = format_model_check(check);
  EXPECT_EQ(check.int8.runs, xnnpack_built() && xnnpack_runs_here()) << report;
  EXPECT_NE(report.find("int8       xnnpack-int8 with ranges " + ranges.string() + ": " +
                        (check.int8.runs ? "yes, runs as xnnpack-int8" : "no: ")),
            std::string::npos)
      << report;
  if (!xnnpack_built() || !xnnpack_runs_here()) return;
  const fs::path missing = dir_ / "absent.ranges";
  const ModelCheck without = check_model({model_, {}, missing});
  const std::string text = format_model_check(without);
  EXPECT_TRUE(without.usable()) << text;
  EXPECT_FALSE(without.int8.runs);
  EXPECT_NE(text.find("int8       xnnpack-int8 with ranges " + missing.string() +
                      ": no: " + missing.string()),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("make them with scripts/calibrate_int8.sh"), std::string::npos) << text;
}

// Anchors cut short (a file of another model, or damaged): named with both counts, and the engines
// are not started on a model that cannot be decoded.
TEST_F(ModelCheckTest, AnchorsOfAnotherCountAreNamedWithBothCounts) {
  const fs::path cut = dir_ / "cut.anchors.csv";
  {
    std::ifstream in(anchors_);
    std::ofstream out(cut);
    std::string line;
    int rows = 0;
    while (std::getline(in, line)) {
      const bool data = !line.empty() && line[0] != '#';
      if (data && ++rows > 1900) break;
      out << line << '\n';
    }
  }
  const ModelCheck check = check_model({model_, cut, {}});
  EXPECT_FALSE(check.usable());
  EXPECT_EQ(check.anchors_in_file, 1900);
  EXPECT_TRUE(any_problem_with(
      check, "anchors: " + cut.string() + " has 1900 rows, the model's outputs 1917"))
      << format_model_check(check);
  EXPECT_TRUE(check.engines.empty());
  EXPECT_NE(format_model_check(check).find("verdict    not usable (1 problem(s) above)\n"),
            std::string::npos);
}

// A file that is no ONNX model, with no anchors beside it: both named, nothing run.
TEST_F(ModelCheckTest, AFileThatIsNoModelIsNamedAsSuch) {
  const fs::path text = dir_ / "notes.onnx";
  std::ofstream(text) << "not a model\n";
  const ModelCheck check = check_model({text, {}, {}});
  EXPECT_FALSE(check.usable());
  EXPECT_TRUE(check.outputs.empty());
  EXPECT_TRUE(any_problem_with(check, "model: OpenCV cannot load or run it"));
  EXPECT_TRUE(any_problem_with(check, "anchors: " + (dir_ / "notes.anchors.csv").string()));
  EXPECT_EQ(check.checksums, "none (no notes.sha256 beside the model)");
}

// A model damaged after download: its checksum names it, before anything else is believed.
TEST_F(ModelCheckTest, AChangedModelFailsItsChecksum) {
  const fs::path copy = dir_ / "ssdlite_mobilenet_v2_coco.onnx";
  fs::copy_file(model_, copy);
  fs::copy_file(anchors_, dir_ / "ssdlite_mobilenet_v2_coco.anchors.csv");
  fs::copy_file(test::source_path("models/ssdlite_mobilenet_v2_coco.sha256"),
                dir_ / "ssdlite_mobilenet_v2_coco.sha256");
  {
    std::fstream file(copy, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(copy) / 2));
    const char zeros[16] = {};
    file.write(zeros, sizeof zeros);
  }
  const ModelCheck check = check_model({copy, {}, {}});
  EXPECT_EQ(check.checksums, "FAILED");
  EXPECT_TRUE(any_problem_with(check, "checksums: ")) << format_model_check(check);
  EXPECT_FALSE(check.usable());
}

// No file at all: the one error of the command (exit code bad_model), naming the path.
TEST_F(ModelCheckTest, AMissingModelIsAnErrorNamingIt) {
  try {
    check_model({dir_ / "absent.onnx", {}, {}});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    EXPECT_NE(std::string(e.what()).find("absent.onnx"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rtmot::detector
