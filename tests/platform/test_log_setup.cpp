// --log-level and --log-format read their names from one table each (platform/log_setup.hpp).
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>
#include <string>

#include "platform/log_setup.hpp"
#include "shared_data.hpp"

namespace rtmot::platform {
namespace {

template <typename Names>
std::string joined(const Names& names, const std::string& separator) {
  std::string text;
  for (const auto& entry : names.entries()) {
    text += (text.empty() ? "" : separator) + std::string(entry.second);
  }
  return text;
}

// Each name sets the level spdlog itself gives that name (what --log-level did before the table).
TEST(LogSetup, EveryLevelNameSetsSpdlogsLevelOfThatName) {
  const auto before = spdlog::get_level();
  for (const auto& [level, name] : kLogLevelNames.entries()) {
    SCOPED_TRACE(std::string(name));
    set_log_level(level);
    EXPECT_EQ(spdlog::get_level(), spdlog::level::from_str(std::string(name)));
  }
  spdlog::set_level(before);
  EXPECT_EQ(kLogLevelNames.alternatives(), "trace, debug, info, warn, error or off");
  EXPECT_EQ(kLogFormatNames.alternatives(), "text or json");
}

// docs/config.md lists the names the flags accept.
TEST(LogSetup, DocsListTheTablesNames) {
  std::ifstream in(test::source_path("docs/config.md"));
  std::stringstream docs;
  docs << in.rdbuf();
  EXPECT_NE(docs.str().find("`--log-level " + joined(kLogLevelNames, "|") + "`"),
            std::string::npos);
  EXPECT_NE(docs.str().find("`--log-format " + joined(kLogFormatNames, "|") + "`"),
            std::string::npos);
}

}  // namespace
}  // namespace rtmot::platform
