// Where a relative input path is looked for (common/input_path.hpp): the config file's folder
// first, then the working directory, then the installed data folder; what was tried is reported.
#include "common/input_path.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace rtmot {
namespace {

class InputPath : public ::testing::Test {
 protected:
  std::filesystem::path folder_ = std::filesystem::path(::testing::TempDir()) /
                                  ("rtmot-input-path-" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(folder_ / "configs"); }
  void TearDown() override { std::filesystem::remove_all(folder_); }
};

TEST_F(InputPath, ConfigFolderComesFirstThenWorkingDirectoryThenInstalledData) {
  const auto candidates = input_path_candidates("../models/m.onnx", folder_ / "configs", "models");
  ASSERT_GE(candidates.size(), 4U);
  EXPECT_EQ(candidates[0], folder_ / "models/m.onnx");  // lexically normal: no "configs/.."
  EXPECT_EQ(candidates[1], std::filesystem::path("../models/m.onnx"));
  EXPECT_EQ(candidates[2], (installed_data_dir() / "../models/m.onnx").lexically_normal());
  EXPECT_EQ(candidates[3], installed_data_dir() / "models/m.onnx");
  // The binary's own tree: <prefix>/bin/x -> <prefix>/share/rtmot.
  EXPECT_EQ(installed_data_dir().filename(), "rtmot");
  EXPECT_EQ(input_path_candidates("/abs/m.onnx", folder_, "models"),
            std::vector<std::filesystem::path>{"/abs/m.onnx"});
}

TEST_F(InputPath, FoundBesideTheConfigWhateverTheWorkingDirectory) {
  std::filesystem::create_directories(folder_ / "models");
  std::ofstream(folder_ / "models/m.onnx") << "x";
  std::string tried;
  EXPECT_EQ(resolve_input_path("../models/m.onnx", folder_ / "configs", "models", tried),
            (folder_ / "models/m.onnx").string());
  EXPECT_EQ(tried, "");
}

TEST_F(InputPath, NotFoundKeepsTheValueAndListsEveryPlaceTried) {
  std::string tried;
  EXPECT_EQ(resolve_input_path("nowhere/m.onnx", folder_ / "configs", "models", tried),
            "nowhere/m.onnx");
  EXPECT_NE(tried.find((folder_ / "configs/nowhere/m.onnx").string()), std::string::npos) << tried;
  EXPECT_NE(tried.find(", nowhere/m.onnx"), std::string::npos) << tried;
  EXPECT_NE(tried.find((installed_data_dir() / "models/m.onnx").string()), std::string::npos)
      << tried;
}

}  // namespace
}  // namespace rtmot
