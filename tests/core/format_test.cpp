// Numbers as mvw's messages and reports show them (mvw/core/Format.h).
#include <gtest/gtest.h>

#include "mvw/core/Format.h"

namespace mvw {
namespace {

TEST(Format, ShortNumber) {
  EXPECT_EQ(shortNumber(0.5), "0.5");
  EXPECT_EQ(shortNumber(2.0), "2");
  EXPECT_EQ(shortNumber(1e-300), "1e-300");
  EXPECT_EQ(shortNumber(2.0615528, 4), "2.062");
  EXPECT_EQ(shortNumber(41.0, 4), "41");
}

TEST(Format, FixedNumber) {
  EXPECT_EQ(fixedNumber(12.5, 1), "12.5");
  EXPECT_EQ(fixedNumber(100.0, 1), "100.0");
  EXPECT_EQ(fixedNumber(-10.25, 3), "-10.250");
  EXPECT_EQ(fixedNumber(0.75, 4), "0.7500");
  EXPECT_EQ(fixedNumber(-0.0, 1), "-0.0");  // as printf shows it
  EXPECT_EQ(fixedNumber(17.0, 0), "17");
  EXPECT_EQ(fixedNumber(1e300, 0).size(), 301u);  // every digit, none cut off
}

}  // namespace
TEST(Format, CountOf) {
  EXPECT_EQ(countOf(0, "instance"), "0 instances");
  EXPECT_EQ(countOf(1, "instance"), "1 instance");
  EXPECT_EQ(countOf(2, "view"), "2 views");
  EXPECT_EQ(countOf(1, "study", "studies"), "1 study");
  EXPECT_EQ(countOf(3, "study", "studies"), "3 studies");
  EXPECT_EQ(countOf(2, "series", "series"), "2 series");
}

TEST(Format, Printable) {
  EXPECT_EQ(printable("plain text, 1.5 mm"), "plain text, 1.5 mm");
  EXPECT_EQ(printable(std::string("a\x1b[2Jb\rc\nd\te\x7f\0f", 15)),
            "a\\x1b[2Jb\\x0dc\\x0ad\\x09e\\x7f\\x00f");
  EXPECT_EQ(printable("M\xc3\xbcller"), "M\xc3\xbcller");  // UTF-8 as it is
}

TEST(Format, Clipped) {
  EXPECT_EQ(clipped("short", 12), "short");
  EXPECT_EQ(clipped("exactly12chr", 12), "exactly12chr");
  EXPECT_EQ(clipped("P-0001234567890", 12), "P-0001234...");
  EXPECT_EQ(clipped("abcdef", 2), "ab");
}

}  // namespace mvw
