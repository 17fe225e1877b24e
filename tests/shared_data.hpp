#pragma once
// Locating the test data in ../shared. A test whose data is missing fails (never skips) and names
// the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace rtmot::test {

inline std::filesystem::path shared_path(const std::string& relative) {
  return std::filesystem::path(RTMOT_SHARED_DIR) / relative;
}

inline std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(RTMOT_SOURCE_DIR) / relative;
}

/// Use as: `auto p = shared_path("data/x"); REQUIRE_FILE(p);`
#define RTMOT_REQUIRE_FILE(path)                                                        \
  do {                                                                                  \
    if (!std::filesystem::exists(path)) FAIL() << "missing test data file: " << (path); \
  } while (0)

}  // namespace rtmot::test
