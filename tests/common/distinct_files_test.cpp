// An output that is an input or another output is refused by its identity, however it is spelled:
// the same file through symbolic and hard links, or one new path written two ways.
#include "common/distinct_files.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"

namespace rtmot {
namespace {

namespace fs = std::filesystem;

class DistinctFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rtmot_distinct_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "sub");
    std::ofstream(dir_ / "det.txt") << "1,-1,10,20,30,40,0.9,-1,-1,-1\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The error's text, or "" when the files were accepted.
  static std::string refusal(const std::vector<NamedFile>& inputs,
                             const std::vector<NamedFile>& outputs) {
    try {
      check_distinct_files(inputs, outputs);
    } catch (const InputError& error) {
      EXPECT_EQ(error.exit_code(), ExitCode::bad_input);
      return error.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(DistinctFiles, AnOutputNamingAnInputThroughLinksIsRefused) {
  const NamedFile det{dir_ / "det.txt", "--det-file"};
  EXPECT_NE(
      refusal({det}, {{dir_ / "det.txt", "--jsonl"}}).find("same file as the input --det-file"),
      std::string::npos);
  EXPECT_NE(refusal({det}, {{dir_ / "sub/../det.txt", "--jsonl"}}), "");
  fs::create_symlink(dir_ / "det.txt", dir_ / "link.txt");
  EXPECT_NE(refusal({det}, {{dir_ / "link.txt", "--report"}}).find("--report"), std::string::npos);
  fs::create_hard_link(dir_ / "det.txt", dir_ / "hard.txt");
  EXPECT_NE(refusal({det}, {{dir_ / "hard.txt", "--binary"}}), "");
  const fs::path here = fs::current_path();
  fs::current_path(dir_);
  EXPECT_NE(refusal({det}, {{"det.txt", "--jsonl"}}), "");  // relative against absolute
  fs::current_path(here);
}

TEST_F(DistinctFiles, TwoOutputsNamingOneNewFileAreRefused) {
  EXPECT_NE(refusal({}, {{dir_ / "out.jsonl", "--jsonl"}, {dir_ / "sub/../out.jsonl", "--binary"}})
                .find("same file as the output --jsonl"),
            std::string::npos);
  EXPECT_NE(refusal({}, {{dir_ / "new/a", "--jsonl"}, {dir_ / "new/./a", "--binary"}}), "");
}

TEST_F(DistinctFiles, DistinctAndAbsentFilesAreAccepted) {
  EXPECT_EQ(
      refusal({{dir_ / "det.txt", "--det-file"}, {"", "--config"}},
              {{dir_ / "out.jsonl", "--jsonl"}, {dir_ / "out.bin", "--binary"}, {"", "--report"}}),
      "");
  // A copy is another file: same bytes, another inode.
  fs::copy_file(dir_ / "det.txt", dir_ / "copy.txt");
  EXPECT_EQ(refusal({{dir_ / "det.txt", "--det-file"}}, {{dir_ / "copy.txt", "--jsonl"}}), "");
}

}  // namespace
}  // namespace rtmot
