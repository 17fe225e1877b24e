#include "common/utf8.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rtmot {
namespace {

TEST(Utf8, AcceptsEveryWellFormedLength) {
  // ASCII, é (2 bytes), € (3), the last code point before the surrogates, U+10000 and U+10FFFF.
  for (const std::string text :
       {"door",
        "Entr\xC3\xA9"
        "e",
        "\xE2\x82\xAC", "\xED\x9F\xBF", "\xF0\x90\x80\x80", "\xF4\x8F\xBF\xBF", ""}) {
    EXPECT_EQ(first_invalid_utf8(text), std::nullopt) << text;
    EXPECT_EQ(replace_invalid_utf8(text), text);
  }
}

TEST(Utf8, FindsTheFirstInvalidByte) {
  EXPECT_EQ(first_invalid_utf8("Entr\xE9"
                               "e"),
            4U);                                          // Latin-1 é
  EXPECT_EQ(first_invalid_utf8("ab\x80"), 2U);            // a stray continuation byte
  EXPECT_EQ(first_invalid_utf8("\xC3"), 0U);              // a lead byte cut off
  EXPECT_EQ(first_invalid_utf8("\xC0\xAF"), 0U);          // overlong '/'
  EXPECT_EQ(first_invalid_utf8("\xE0\x80\xAF"), 0U);      // overlong, three bytes
  EXPECT_EQ(first_invalid_utf8("x\xED\xA0\x80"), 1U);     // a surrogate (U+D800)
  EXPECT_EQ(first_invalid_utf8("\xF4\x90\x80\x80"), 0U);  // above U+10FFFF
  EXPECT_EQ(first_invalid_utf8("\xF5\x80\x80\x80"), 0U);  // no such lead byte
  EXPECT_EQ(first_invalid_utf8("\xE2\x82"
                               "A"),
            0U);  // a continuation missing
}

TEST(Utf8, ReplacesEachInvalidByteAndKeepsTheRest) {
  EXPECT_EQ(replace_invalid_utf8("Entr\xE9"
                                 "e \xE2\x82\xAC"),
            "Entr\xEF\xBF\xBD"
            "e \xE2\x82\xAC");
  EXPECT_EQ(replace_invalid_utf8("\xFF\xFE"), "\xEF\xBF\xBD\xEF\xBF\xBD");
}

}  // namespace
}  // namespace rtmot
