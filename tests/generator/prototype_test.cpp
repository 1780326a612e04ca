// Parameter lists of generated entry points and their line breaking (generator/emit/prototype):
// literal expected text, as the generated headers show it.

#include "generator/emit/prototype.hpp"

#include <string>

#include <gtest/gtest.h>

namespace modelgen::gen {
namespace {

TEST(Prototype, ParameterListHasConstInputsThenOutputs) {
  EXPECT_EQ(parameter_list({"q", "beta"}, {"tau"}, Scalar::kDouble),
            "const double* q, const double* beta, double* tau");
  EXPECT_EQ(parameter_list({"q"}, {"sin_q", "cos_q"}, Scalar::kFloat),
            "const float* q, float* sin_q, float* cos_q");
}

TEST(Prototype, ShortLinesStayAsTheyAre) {
  const std::string line = "void f(const double* q, double* W) {";
  EXPECT_EQ(wrap_parameters(line, 100), line);
  EXPECT_EQ(wrap_parameters(line, line.size()), line);
}

TEST(Prototype, LongParameterListsBreakAfterCommasAlignedToTheParenthesis) {
  EXPECT_EQ(wrap_parameters("void name(aaaa, bbbb, cccc, dddd) {", 24),
            "void name(aaaa, bbbb,\n"
            "          cccc, dddd) {");
  // Every line is filled greedily; the rest of the line stays with the last parameter.
  EXPECT_EQ(wrap_parameters("void name(aaaa, bbbb, cccc, dddd, eeee);", 22),
            "void name(aaaa, bbbb,\n"
            "          cccc, dddd,\n"
            "          eeee);");
}

TEST(Prototype, ParameterLongerThanTheWidthGetsItsOwnLine) {
  EXPECT_EQ(wrap_parameters("f(a, bbbbbbbbbbbbbbbb, c)", 10),
            "f(a,\n"
            "  bbbbbbbbbbbbbbbb,\n"
            "  c)");
}

}  // namespace
}  // namespace modelgen::gen
