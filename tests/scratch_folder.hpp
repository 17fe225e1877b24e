#pragma once
// A test's own folder under the test temp dir, removed when the test passed. Fixtures used to make
// "rtmot-NAME-PID-TEST" folders and leave them: every run of the suite left a few hundred behind.
// A failed test keeps its folder (its logs and outputs are what a reader of the failure wants) and
// says where it is.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

namespace rtmot::test {

class ScratchFolder {
 public:
  /// TempDir()/rtmot-<kind>-<pid>-<the current test's name>, created.
  explicit ScratchFolder(const std::string& kind)
      : path_(std::filesystem::path(::testing::TempDir()) /
              ("rtmot-" + kind + "-" + std::to_string(::getpid()) + "-" + current_test_name())) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    if (::testing::Test::HasFailure()) {
      std::cerr << "kept for the failure: " << path_.string() << "\n";
      return;
    }
    std::error_code ignored;  // a folder that cannot be removed must not fail a passed test
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  // A parameterized test's name holds a '/' ("Case/param"): in the path it made a subfolder,
  // and removing the path left its parent behind on every run.
  static std::string current_test_name() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info == nullptr ? "outside-a-test" : info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    return name;
  }

  std::filesystem::path path_;
};

}  // namespace rtmot::test
