#include "palpa/report/csv_number.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace palpa::report {
namespace {

TEST(CsvNumber, EachUnitHasItsDecimals) {
  EXPECT_EQ(csv_number(30.000000000000004, CsvUnit::Millimetre), "30.0");
  EXPECT_EQ(csv_number(2.8349, CsvUnit::Millimetre), "2.8");
  EXPECT_EQ(csv_number(7.0789, CsvUnit::Newton), "7.08");
  EXPECT_EQ(csv_number(127.004999, CsvUnit::Second), "127.00");
  EXPECT_EQ(csv_number(0.6583, CsvUnit::Fraction), "0.658");
  EXPECT_EQ(csv_number(1.0, CsvUnit::Fraction), "1.000");
  EXPECT_EQ(csv_number(1.9876, CsvUnit::Ratio), "1.99");
  EXPECT_EQ(csv_number(65.83, CsvUnit::Score100), "65.8");
  EXPECT_EQ(csv_number(-0.18616894171033568, CsvUnit::Cusum), "-0.19");
}

TEST(CsvNumber, RoundsFromTheExactBinaryValue) {
  // 0.6125 is stored as 0.61250000000000004441: above the tie, so up.
  EXPECT_EQ(csv_number(0.6125, CsvUnit::Fraction), "0.613");
  // 2.675 is stored as 2.67499999999999982236: below the tie, so down.
  EXPECT_EQ(csv_number(2.675, CsvUnit::Newton), "2.67");
}

TEST(CsvNumber, NoNegativeZeroAndEmptyForNotANumber) {
  EXPECT_EQ(csv_number(-0.04, CsvUnit::Millimetre), "0.0");
  EXPECT_EQ(csv_number(-0.0, CsvUnit::Fraction), "0.000");
  EXPECT_EQ(csv_number(-0.004, CsvUnit::Cusum), "0.00");
  EXPECT_EQ(csv_number(-0.05, CsvUnit::Millimetre), "-0.1");  // -0.05000000000000000278: a real -0.1
  EXPECT_EQ(csv_number(std::nan(""), CsvUnit::Millimetre), "");
  EXPECT_EQ(csv_number(std::numeric_limits<double>::infinity(), CsvUnit::Second), "");
  EXPECT_EQ(csv_number(-std::numeric_limits<double>::infinity(), CsvUnit::Newton), "");
}

}  // namespace
}  // namespace palpa::report
