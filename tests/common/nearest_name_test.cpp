// "Did you mean": the nearest valid name only when it is close, and no guess otherwise.
#include "common/nearest_name.hpp"

#include <gtest/gtest.h>

namespace rtmot {
namespace {

const std::vector<std::string> kFlags = {"--config", "--detector-threads", "--jsonl", "--log-level",
                                         "--port",   "--max-frames"};

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("", ""), 0U);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3U);
  EXPECT_EQ(edit_distance("max_age", "max_ag"), 1U);
  EXPECT_EQ(edit_distance("abc", ""), 3U);
}

TEST(NearestName, NamesTheCloseTypo) {
  EXPECT_EQ(nearest_name("--confg", kFlags), "--config");
  EXPECT_EQ(nearest_name("--log-levl", kFlags), "--log-level");
  EXPECT_EQ(nearest_name("--prot", kFlags), "--port");
}

TEST(NearestName, NamesTheOnlyFlagHoldingTheWordTyped) {
  EXPECT_EQ(nearest_name("--threads", kFlags), "--detector-threads");
  EXPECT_EQ(nearest_name("--frames", kFlags), "--max-frames");
}

TEST(NearestName, GuessesNothingWhenNothingIsClose) {
  EXPECT_EQ(nearest_name("--zzzzzz", kFlags), std::nullopt);
  EXPECT_EQ(nearest_name("--verbose", kFlags), std::nullopt);
  EXPECT_EQ(nearest_name("--config", kFlags), std::nullopt);  // valid: not a typo
  EXPECT_EQ(nearest_name("--x", {}), std::nullopt);
  // A word two names hold: no guess between them.
  EXPECT_EQ(nearest_name("--level", {"--log-level", "--noise-level"}), std::nullopt);
}

TEST(DidYouMean, IsEmptyOrOneParenthesis) {
  EXPECT_EQ(did_you_mean("traker", {"source", "tracker"}), " (did you mean tracker?)");
  EXPECT_EQ(did_you_mean("zzzzzz", {"source", "tracker"}), "");
}

}  // namespace
}  // namespace rtmot
