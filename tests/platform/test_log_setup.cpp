// --log-level and --log-format read their names from one table each (platform/log_setup.hpp).
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>
#include <string>

#include "platform/json_log_text.hpp"
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

std::string json_content(std::string_view text) {
  std::string out;
  append_json_string_content(text, out);
  return out;
}

// A JSON log line is valid UTF-8 whatever bytes a file name holds: well-formed sequences pass as
// they are, every other byte becomes the text \xNN (JSON "\\xNN"), which names the byte.
TEST(JsonLogText, BytesThatAreNotUtf8AreWrittenAsTheirHexValue) {
  EXPECT_EQ(json_content("caf\xC3\xA9 \xF0\x9F\x98\x80"), "caf\xC3\xA9 \xF0\x9F\x98\x80");
  EXPECT_EQ(json_content("caf\xE9.txt"), "caf\\\\xE9.txt");          // Latin-1: a lone lead byte
  EXPECT_EQ(json_content("\xC0\xAF"), "\\\\xC0\\\\xAF");             // overlong '/'
  EXPECT_EQ(json_content("\xED\xA0\x80"), "\\\\xED\\\\xA0\\\\x80");  // a surrogate
  EXPECT_EQ(json_content("\xF4\x90\x80\x80"), "\\\\xF4\\\\x90\\\\x80\\\\x80");  // > U+10FFFF
  EXPECT_EQ(json_content("\xE2\x82"), "\\\\xE2\\\\x82");  // cut at the end of the text
  EXPECT_EQ(json_content("\x80x"), "\\\\x80x");           // a continuation byte alone
}

TEST(JsonLogText, QuotesBackslashesAndControlCharactersAreEscaped) {
  EXPECT_EQ(json_content(std::string("a\"b\\c\n\t\r\x01", 9)), "a\\\"b\\\\c\\n\\t\\r\\u0001");
  EXPECT_EQ(json_content(std::string("\0", 1)), "\\u0000");
}

}  // namespace
}  // namespace rtmot::platform
