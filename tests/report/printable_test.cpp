#include "palpa/report/printable.hpp"

#include <gtest/gtest.h>

namespace palpa::report {
namespace {

TEST(Printable, PlainTextAndUtf8StayAsTheyAre) {
  EXPECT_EQ(printable("room-1 Zoë 東京"), "room-1 Zoë 東京");
  EXPECT_TRUE(is_printable("room-1 Zoë 東京"));
}

TEST(Printable, EscapeSequencesCannotReachATerminal) {
  const std::string clear_and_red = "id\x1b[2J\x1b[31mFAKE";
  EXPECT_EQ(printable(clear_and_red), "id\\x1b[2J\\x1b[31mFAKE");
  EXPECT_FALSE(is_printable(clear_and_red));
  EXPECT_EQ(printable(std::string("ali\0ce", 6)), "ali\\x00ce");
  EXPECT_EQ(printable("a\tb\nc\x7f"), "a\\x09b\\x0ac\\x7f");
  EXPECT_EQ(printable("c1\u0085"), "c1\\x85");  // NEL, a C1 control, as UTF-8
}

TEST(Printable, BidirectionalControlsAreShownByTheirCodePoint) {
  // Trojan Source: U+202E reverses what follows on screen.
  EXPECT_EQ(printable("\u202eecila"), "\\u{202e}ecila");
  EXPECT_EQ(printable("a\u2066b\u2069c\u200f"), "a\\u{2066}b\\u{2069}c\\u{200f}");
  EXPECT_EQ(printable("line\u2028sep"), "line\\u{2028}sep");
  EXPECT_FALSE(is_printable("x\u202ay"));
}

TEST(Printable, InvisibleCharactersThatMakeLookAlikeNamesAreShown) {
  EXPECT_EQ(printable("al\u200bice"), "al\\u{200b}ice");      // zero-width space
  EXPECT_EQ(printable("\ufeffbob"), "\\u{feff}bob");          // byte-order mark
  EXPECT_EQ(printable("a\u00adb\u061cc"), "a\\xadb\\u{061c}c");  // soft hyphen, Arabic letter mark
  EXPECT_EQ(printable("x\U000E0041y"), "x\\u{e0041}y");       // a tag character
  // Default-ignorable and format characters beyond the common ones, and the blank braille
  // pattern: each renders as nothing after "alice".
  EXPECT_EQ(printable("alice\U0001D173"), "alice\\u{1d173}");  // musical symbol begin beam
  EXPECT_EQ(printable("alice\U0001BCA0"), "alice\\u{1bca0}");  // shorthand format letter overlap
  EXPECT_EQ(printable("alice\u2800"), "alice\\u{2800}");       // braille pattern blank
  EXPECT_EQ(printable("alice\u0600"), "alice\\u{0600}");       // Arabic number sign
  EXPECT_EQ(printable("\u3164"), "\\u{3164}");                // Hangul filler
  EXPECT_TRUE(is_printable("r\u03bfom"));  // a Greek omicron is visible: shown as it is
}

TEST(Printable, InvalidUtf8IsEscapedByteByByte) {
  EXPECT_EQ(printable("a\xff" "b"), "a\\xffb");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");            // overlong "/"
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");   // a surrogate
  EXPECT_EQ(printable("cut\xe6\x9d"), "cut\\xe6\\x9d");      // a sequence cut short
  EXPECT_FALSE(is_printable("a\xff"));
}

TEST(Printable, LongTextIsShortenedByCodePoints) {
  EXPECT_EQ(printable(std::string(10, 'x'), 4), "xxxx\u2026");
  EXPECT_EQ(printable("ééééé", 3), "ééé\u2026");
  EXPECT_EQ(printable("abc", 3), "abc");
  EXPECT_EQ(printable(std::string(100000, 'x')).size(), 120 + std::string("\u2026").size());
}

}  // namespace
}  // namespace palpa::report
