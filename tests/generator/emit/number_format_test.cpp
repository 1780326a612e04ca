// Numeric literals in generated code: literal text for hand-picked values, and on many random
// doubles the properties every literal must have: it reads back as exactly the same value
// (double, or the value rounded to float), and it is a floating-point literal of the right type.

#include "generator/emit/number_format.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace modelgen::gen {
namespace {

// True if `text` is a C++ floating literal (with an optional leading minus) without suffix:
// digits with a '.' or an exponent, nothing else.
bool is_floating_literal(const std::string& text) {
  std::size_t i = 0;
  if (i < text.size() && text[i] == '-') ++i;
  bool digits = false, dot = false, exponent = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c >= '0' && c <= '9') {
      digits = true;
    } else if (c == '.' && !dot && !exponent) {
      dot = true;
    } else if (c == 'e' && digits && !exponent) {
      exponent = true;
      if (i + 1 < text.size() && (text[i + 1] == '+' || text[i + 1] == '-')) ++i;
      if (i + 1 >= text.size()) return false;
    } else {
      return false;
    }
  }
  return digits && (dot || exponent);
}

// Reads a double literal back; fails the test unless all of `text` is consumed.
double read_double(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  EXPECT_EQ(end, text.c_str() + text.size()) << "'" << text << "' is not entirely a number";
  return value;
}

// Reads a float literal back; requires the "f" suffix.
float read_float(const std::string& text) {
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.back(), 'f') << text;
  const std::string digits = text.substr(0, text.size() - 1);
  EXPECT_TRUE(is_floating_literal(digits)) << text;
  char* end = nullptr;
  const float value = std::strtof(digits.c_str(), &end);
  EXPECT_EQ(end, digits.c_str() + digits.size()) << "'" << text << "' is not entirely a number";
  return value;
}

TEST(NumberFormat, ScalarNames) {
  EXPECT_STREQ(scalar_name(Scalar::kDouble), "double");
  EXPECT_STREQ(scalar_name(Scalar::kFloat), "float");
}

TEST(NumberFormat, DoubleLiterals) {
  EXPECT_EQ(format_literal(0.225, Scalar::kDouble), "0.225");
  EXPECT_EQ(format_literal(2.0, Scalar::kDouble), "2.0");
  EXPECT_EQ(format_literal(1e-5, Scalar::kDouble), "1e-05");
  EXPECT_EQ(format_literal(-3.5, Scalar::kDouble), "-3.5");
  EXPECT_EQ(format_literal(0.0, Scalar::kDouble), "0.0");
  EXPECT_EQ(format_literal(1.0, Scalar::kDouble), "1.0");
  EXPECT_EQ(format_literal(-1.0, Scalar::kDouble), "-1.0");
  EXPECT_EQ(format_literal(0.1, Scalar::kDouble), "0.1");
  EXPECT_EQ(format_literal(1500.0, Scalar::kDouble), "1500.0");
  EXPECT_EQ(format_literal(-0.5, Scalar::kDouble), "-0.5");
}

TEST(NumberFormat, FloatLiterals) {
  EXPECT_EQ(format_literal(0.225, Scalar::kFloat), "0.225f");
  EXPECT_EQ(format_literal(2.0, Scalar::kFloat), "2.0f");
  EXPECT_EQ(format_literal(1e-5, Scalar::kFloat), "1e-05f");
  EXPECT_EQ(format_literal(-3.5, Scalar::kFloat), "-3.5f");
  EXPECT_EQ(format_literal(0.0, Scalar::kFloat), "0.0f");
  EXPECT_EQ(format_literal(0.1, Scalar::kFloat), "0.1f");
}

TEST(NumberFormat, FloatIsRoundedToFloatFirst) {
  // 0.1 + 1e-12 is a different double from 0.1 but the same float: the float literal must be
  // the shortest text of the float, not of the double.
  EXPECT_EQ(format_literal(0.1 + 1e-12, Scalar::kFloat), "0.1f");
  EXPECT_NE(format_literal(0.1 + 1e-12, Scalar::kDouble), "0.1");
  // pi: 17 significant digits as a double, 8 or fewer as a float.
  const std::string pi_double = format_literal(M_PI, Scalar::kDouble);
  const std::string pi_float = format_literal(M_PI, Scalar::kFloat);
  EXPECT_EQ(read_double(pi_double), M_PI);
  EXPECT_EQ(read_float(pi_float), static_cast<float>(M_PI));
  EXPECT_LT(pi_float.size(), pi_double.size());
}

TEST(NumberFormat, ShortestText) {
  // 0.3 is not 0.1 + 0.2 in binary; each prints with as few digits as read back exactly.
  EXPECT_EQ(format_literal(0.3, Scalar::kDouble), "0.3");
  EXPECT_EQ(format_literal(0.1 + 0.2, Scalar::kDouble), "0.30000000000000004");
}

TEST(NumberFormat, LargeAndTinyMagnitudesStayFloatingLiterals) {
  for (double v : {1e15, 1e16, 1e20, 1e300, -1e300, 1e-300, 4.9e-324, 123456789012345678.0}) {
    const std::string text = format_literal(v, Scalar::kDouble);
    EXPECT_TRUE(is_floating_literal(text)) << text;
    EXPECT_EQ(read_double(text), v) << text;
  }
  for (double v : {1e15, 1e20, 3.0e38, 1e-30, -1e-30}) {
    const std::string text = format_literal(v, Scalar::kFloat);
    EXPECT_EQ(read_float(text), static_cast<float>(v)) << text;
  }
}

TEST(NumberFormat, FloatOutOfRangeIsNotPrintedAsInfinity) {
  // 1e300 is a finite double but overflows float: "inff" would not compile. Either refuse
  // (a generator bug, std::logic_error) or print something that is a floating literal.
  std::string text;
  try {
    text = format_literal(1e300, Scalar::kFloat);
  } catch (const std::logic_error&) {
    return;
  }
  EXPECT_EQ(text.find("inf"), std::string::npos) << text;
  EXPECT_TRUE(is_floating_literal(text.substr(0, text.size() - 1))) << text;
}

TEST(NumberFormat, RandomDoublesRoundTrip) {
  std::mt19937_64 engine(20240611);
  std::uniform_int_distribution<int> exponent(-40, 40);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  for (int i = 0; i < 20000; ++i) {
    const double value = mantissa(engine) * std::pow(10.0, exponent(engine));
    const std::string text = format_literal(value, Scalar::kDouble);
    ASSERT_TRUE(is_floating_literal(text)) << text;
    ASSERT_EQ(read_double(text), value) << text;
    ASSERT_FALSE(testing::Test::HasFailure()) << text;
    // Values beyond float's range are covered by FloatOutOfRangeIsNotPrintedAsInfinity.
    if (!std::isfinite(static_cast<float>(value))) continue;
    const std::string float_text = format_literal(value, Scalar::kFloat);
    ASSERT_EQ(read_float(float_text), static_cast<float>(value)) << float_text;
    ASSERT_FALSE(testing::Test::HasFailure()) << float_text;
  }
}

TEST(NumberFormat, RandomBitPatternsRoundTrip) {
  // Every finite double, not only "nice" ones: uniformly random bit patterns.
  std::mt19937_64 engine(7);
  int checked = 0;
  while (checked < 20000) {
    const double value = std::bit_cast<double>(static_cast<std::uint64_t>(engine()));
    if (!std::isfinite(value)) continue;
    ++checked;
    const std::string text = format_literal(value, Scalar::kDouble);
    ASSERT_TRUE(is_floating_literal(text)) << text;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(read_double(text)), std::bit_cast<std::uint64_t>(value))
        << text;
  }
}

TEST(NumberFormat, SmallIntegersPrintWithPointZero) {
  for (int n = -1000; n <= 1000; ++n) {
    const std::string expected = std::to_string(n) + ".0";
    EXPECT_EQ(format_literal(n, Scalar::kDouble), expected);
    EXPECT_EQ(format_literal(n, Scalar::kFloat), expected + "f");
  }
}

}  // namespace
}  // namespace modelgen::gen
