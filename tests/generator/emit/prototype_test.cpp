// Prototypes of generated entry points (generator/emit/prototype): parameter lists, their line
// breaking and the documentation of a _sincos variant, as literal text.

#include "generator/emit/prototype.hpp"

#include <string>

#include <gtest/gtest.h>

#include "generator/functions/registry.hpp"

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

TEST(Prototype, SincosVariantIsDocumentedAsAVariantAndWrapped) {
  EmittedFunction variant;
  for (const FunctionEntry& entry : function_registry()) {
    if (std::string(entry.name) == "idim_regressor") variant.entry = &entry;
  }
  ASSERT_NE(variant.entry, nullptr);
  variant.name = "idim_regressor_sincos";
  variant.sincos = true;
  variant.inputs = {"q", "sin_q", "cos_q", "dq", "ddq"};
  variant.outputs = {"W"};
  EXPECT_EQ(function_prototype(variant, Scalar::kDouble, true),
            "// idim_regressor with sin_q, cos_q (kDof each) from joint_sincos(q, ...) instead of\n"
            "// computing them; identical results.\n"
            "void idim_regressor_sincos(const double* q, const double* sin_q, const double* cos_q,\n"
            "                           const double* dq, const double* ddq, double* W)");
  EXPECT_EQ(function_prototype(variant, Scalar::kFloat, false),
            "void idim_regressor_sincos(const float* q, const float* sin_q, const float* cos_q,\n"
            "                           const float* dq, const float* ddq, float* W)");
}

}  // namespace
}  // namespace modelgen::gen
