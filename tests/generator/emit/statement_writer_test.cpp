// Straight-line statements from the DAG: exact lines for small hand-built graphs (derived leaves
// first, shared subexpressions as t0..tN, single-use ones inline, "a - b" for negative terms,
// named outputs, float literals), and on random graphs: the operation counts equal the
// operations in the text, and the text, read by a small interpreter here, computes the same
// values as the DAG.

#include "generator/emit/statement_writer.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {
namespace {

using Lines = std::vector<std::string>;

class StatementWriterTest : public testing::Test {
 protected:
  // Operands print in canonical order (ExprGraph::canonical_before): constants, symbols by name
  // (c1 < p[0] < p[1] < p[2] < q[0] < s1), then operations by height and arguments.
  ExprGraph g;
  const ExprId q0 = g.symbol(Symbol{"q[0]", SymbolKind::kInput, ""});
  const ExprId s1 = g.symbol(Symbol{"s1", SymbolKind::kSin, "q[0]"});
  const ExprId c1 = g.symbol(Symbol{"c1", SymbolKind::kCos, "q[0]"});
  const ExprId p0 = g.symbol(Symbol{"p[0]", SymbolKind::kInput, ""});
  const ExprId p1 = g.symbol(Symbol{"p[1]", SymbolKind::kInput, ""});
  const ExprId p2 = g.symbol(Symbol{"p[2]", SymbolKind::kInput, ""});
};

TEST_F(StatementWriterTest, ConsecutiveScaledCopiesPrintAsOneLoop) {
  // J[2 + k] = Y[1 + k] * t for k < 5 is one loop the compiler vectorizes; a run broken by an
  // index, and a run shorter than four, stay statements. Counted as the products computed.
  std::vector<ExprId> Y;
  for (int k = 0; k < 16; ++k) {
    Y.push_back(g.symbol(Symbol{"Y[" + std::to_string(k) + "]", SymbolKind::kInput, ""}));
  }
  const ExprId t = g.share(g.add(s1, p0));
  std::vector<FunctionOutput> outputs;
  for (int k = 0; k < 5; ++k) outputs.push_back({"J[" + std::to_string(2 + k) + "]", g.mul(Y[1 + k], t), ""});
  outputs.push_back({"J[7]", g.mul(Y[9], t), "M1"});
  for (int k = 0; k < 3; ++k) outputs.push_back({"J[" + std::to_string(8 + k) + "]", g.mul(Y[11 + k], t), ""});
  const FunctionBody body = write_statements(g, outputs, Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "const double t0 = p[0] + s1;",
                            "for (int k = 0; k < 5; ++k) J[2 + k] = Y[1 + k] * t0;",
                            "J[7] = Y[9] * t0;  // M1",
                            "J[8] = Y[11] * t0;",
                            "J[9] = Y[12] * t0;",
                            "J[10] = Y[13] * t0;",
                        }));
  EXPECT_EQ(body.counts.mul, 9);
  EXPECT_EQ(body.counts.add, 1);
}

// Y[0], Y[1], ... as input symbols.
std::vector<ExprId> input_array(ExprGraph& g, const std::string& name, int size) {
  std::vector<ExprId> entries;
  for (int k = 0; k < size; ++k) {
    entries.push_back(g.symbol(Symbol{name + "[" + std::to_string(k) + "]", SymbolKind::kInput, ""}));
  }
  return entries;
}

bool has_loop(const FunctionBody& body) {
  return std::any_of(body.lines.begin(), body.lines.end(),
                     [](const std::string& line) { return line.rfind("for (", 0) == 0; });
}

TEST_F(StatementWriterTest, ScaledCopyLoopsKeepTheSignsAndTheComments) {
  const std::vector<ExprId> Y = input_array(g, "Y", 10);
  const ExprId t = g.share(g.add(s1, p0));
  // Six outputs -(Y[k] t): t is read negated by all, so it is stored negated (t0 = -t) and
  // each output prints as Y[k] * t0, one loop carrying the outputs' comments.
  std::vector<FunctionOutput> negated;
  for (int k = 0; k < 6; ++k) {
    negated.push_back({"J[" + std::to_string(k) + "]", g.neg(g.share(g.mul(Y[k], t))),
                       k == 1 ? "XX1" : (k == 4 ? "MX1" : "")});
  }
  const FunctionBody flipped = write_statements(g, negated, Scalar::kDouble);
  EXPECT_EQ(flipped.lines, (Lines{
                               "const double s1 = std::sin(q[0]);",
                               "const double t0 = -p[0] - s1;",
                               "for (int k = 0; k < 6; ++k) J[0 + k] = Y[0 + k] * t0;  // XX1 MX1",
                           }));
  EXPECT_EQ(flipped.counts.mul, 6);
  EXPECT_EQ(flipped.counts.add, 2);  // the negation and the subtraction of t0
  // Outputs +Y[k] t with t stored negated must print the negation: statements, not a loop.
  std::vector<FunctionOutput> mixed = negated;
  for (int k = 0; k < 4; ++k) {
    mixed.push_back({"J[" + std::to_string(10 + k) + "]", g.share(g.mul(Y[6 + k], t)), ""});
  }
  const FunctionBody both = write_statements(g, mixed, Scalar::kDouble);
  EXPECT_EQ(both.lines[1], "const double t0 = -p[0] - s1;");
  EXPECT_EQ(both.lines[3], "J[10] = -Y[6] * t0;");
  EXPECT_EQ(both.lines.size(), 7u);
  // A derived leaf as the factor: the loop declares it.
  std::vector<FunctionOutput> by_sine;
  for (int k = 0; k < 4; ++k) by_sine.push_back({"J[" + std::to_string(k) + "]", g.mul(Y[k], s1), ""});
  EXPECT_EQ(write_statements(g, by_sine, Scalar::kDouble).lines,
            (Lines{"const double s1 = std::sin(q[0]);",
                   "for (int k = 0; k < 4; ++k) J[0 + k] = Y[0 + k] * s1;"}));
}

TEST_F(StatementWriterTest, AFlatNegatedProductOrASharedOneIsNotALoopEntry) {
  const std::vector<ExprId> Y = input_array(g, "Y", 6);
  const ExprId t = g.share(g.add(s1, p0));
  // -(Y[k] t) built flat is the product -1 * Y[k] * t: three factors, not a scaled copy.
  std::vector<FunctionOutput> flat;
  for (int k = 0; k < 5; ++k) flat.push_back({"J[" + std::to_string(k) + "]", g.neg(g.mul(Y[k], t)), ""});
  EXPECT_FALSE(has_loop(write_statements(g, flat, Scalar::kDouble)));
  // Y[2] t read by another output too is a temporary of its own: the run stops before it.
  std::vector<FunctionOutput> shared;
  for (int k = 0; k < 6; ++k) shared.push_back({"J[" + std::to_string(k) + "]", g.mul(Y[k], t), ""});
  shared.push_back({"W[0]", g.add(g.mul(Y[2], t), p1), ""});
  const FunctionBody body = write_statements(g, shared, Scalar::kDouble);
  EXPECT_FALSE(has_loop(body)) << body.lines[2];
}

TEST_F(StatementWriterTest, LongSumsPrintAsFourParenthesizedGroups) {
  // 40 terms: four independent chains of additions; a group of only negative terms is
  // subtracted whole, so the additions stay 39. 31 terms stay one chain.
  auto sum_of = [&](int positive, int negative) {
    std::vector<ExprId> terms;
    for (int k = 0; k < positive + negative; ++k) {
      const ExprId y = g.symbol(Symbol{"Y[" + std::to_string(100 + k) + "]", SymbolKind::kInput, ""});
      terms.push_back(k < positive ? y : g.neg(y));
    }
    return write_statements(g, {{"W[0]", g.add(terms), ""}}, Scalar::kDouble);
  };
  const FunctionBody grouped = sum_of(30, 10);
  ASSERT_EQ(grouped.lines.size(), 1u);
  const std::string& line = grouped.lines[0];
  EXPECT_EQ(std::count(line.begin(), line.end(), '('), 4) << line;
  EXPECT_EQ(line.rfind("W[0] = (Y[100] + ", 0), 0u) << line;
  EXPECT_NE(line.find(") - (Y[130] + "), std::string::npos) << line;
  EXPECT_EQ(grouped.counts.add, 39);
  for (int k = 100; k < 140; ++k) EXPECT_NE(line.find("Y[" + std::to_string(k) + "]"), std::string::npos);
  const FunctionBody chain = sum_of(31, 0);
  EXPECT_EQ(chain.lines[0].find('('), std::string::npos) << chain.lines[0];
  EXPECT_EQ(chain.counts.add, 30);
}

TEST_F(StatementWriterTest, SharedSubexpressionBecomesATemporary) {
  const ExprId e = g.add(s1, p0);
  const FunctionBody body = write_statements(
      g, {{"W[0]", g.mul(e, q0), "XX1"}, {"W[1]", g.mul(e, p1), ""}, {"W[2]", g.zero(), ""}},
      Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "const double t0 = p[0] + s1;",
                            "W[0] = q[0] * t0;  // XX1",
                            "W[1] = p[1] * t0;",
                            // W[2] is zero for every input: not written (the caller zeroes W).
                        }));
  EXPECT_EQ(body.counts.mul, 2);
  EXPECT_EQ(body.counts.add, 1);
  EXPECT_EQ(body.counts.trig, 1);
}

TEST_F(StatementWriterTest, SingleUseSubexpressionsAreInlined) {
  const ExprId s1_p1 = g.mul(s1, p1);
  const ExprId c1_p0 = g.mul(c1, p0);  // created second, printed first: c1 sorts before p[1]
  const ExprId value = g.add(s1_p1, c1_p0);
  const FunctionBody body = write_statements(g, {{"W[0]", value, "ZZ1"}}, Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "const double c1 = std::cos(q[0]);",
                            "W[0] = c1 * p[0] + p[1] * s1;  // ZZ1",
                        }));
  EXPECT_EQ(body.counts.mul, 2);
  EXPECT_EQ(body.counts.add, 1);
  EXPECT_EQ(body.counts.trig, 2);
}

TEST_F(StatementWriterTest, UnusedDerivedLeavesAreNotDeclared) {
  const FunctionBody body = write_statements(g, {{"tau[0]", g.mul(p0, q0), ""}}, Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{"tau[0] = p[0] * q[0];"}));
  EXPECT_EQ(body.counts.trig, 0);
}

TEST_F(StatementWriterTest, NegativeTermsPrintAsSubtraction) {
  // A sum leads with a positive term: W[2] = -p[0] + p[1] * p[2] prints as p[1] * p[2] - p[0],
  // one operation less. Each negative term is used once (a node used twice would become a
  // temporary).
  const ExprId two_p0 = g.mul(g.constant(2), p0);
  const ExprId minus_p0 = g.neg(p0);
  const FunctionBody body = write_statements(g,
                                             {{"W[0]", g.sub(p0, p1), ""},
                                              {"W[1]", g.sub(two_p0, g.mul(g.constant(3), p1)), ""},
                                              {"W[2]", g.add(minus_p0, g.mul(p1, p2)), ""},
                                              {"W[3]", g.neg(p2), ""},
                                              {"W[4]", g.add(p2, g.constant(-0.5)), ""}},
                                             Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "W[0] = p[0] - p[1];",
                            "W[1] = 2.0 * p[0] - 3.0 * p[1];",
                            "W[2] = p[1] * p[2] - p[0];",
                            "W[3] = -p[2];",
                            "W[4] = p[2] - 0.5;",
                        }));
  for (const std::string& line : body.lines) {
    EXPECT_EQ(line.find("+ -"), std::string::npos) << line;
    EXPECT_EQ(line.find("- -"), std::string::npos) << line;
    EXPECT_EQ(line.find("-1.0 *"), std::string::npos) << line;
  }
  // '*': 0 + 2 + 1 + 0 + 0; '+'/'-' incl. unary: 1 + 1 + 1 + 1 + 1.
  EXPECT_EQ(body.counts.mul, 3);
  EXPECT_EQ(body.counts.add, 5);
  EXPECT_EQ(body.counts.trig, 0);
}

TEST_F(StatementWriterTest, NegativeConstantCountsTheSameAloneAndAsFirstTerm) {
  // "W[0] = -2.0;" and "W[0] = -2.0 - p[0] * p[1];" differ by exactly one '-' and one '*'.
  // Whether the '-' of a negative literal is an operation or not, it must count the same in
  // both lines. With no positive term, the literal leads (its sign costs nothing).
  const ExprId minus_two = g.constant(-2.0);
  const ExprId product = g.neg(g.mul(p0, p1));
  const FunctionBody alone = write_statements(g, {{"W[0]", minus_two, ""}}, Scalar::kDouble);
  const FunctionBody first =
      write_statements(g, {{"W[0]", g.add(product, minus_two), ""}}, Scalar::kDouble);
  ASSERT_EQ(alone.lines, (Lines{"W[0] = -2.0;"}));
  ASSERT_EQ(first.lines, (Lines{"W[0] = -2.0 - p[0] * p[1];"}));
  EXPECT_EQ(first.counts.mul - alone.counts.mul, 1);
  EXPECT_EQ(first.counts.add - alone.counts.add, 1)
      << "alone: " << alone.counts.add << " add, as first term: " << first.counts.add << " add";
}

TEST_F(StatementWriterTest, NegatedInlineSumIsSplicedWithFlippedSigns) {
  // a - (b - c) with (b - c) kept whole by share() but used once: a - b + c.
  const ExprId inner = g.share(g.sub(p1, p2));
  const FunctionBody body = write_statements(g, {{"W[0]", g.sub(p0, inner), ""}}, Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{"W[0] = p[0] - p[1] + p[2];"}));
  EXPECT_EQ(body.counts.add, 2);
  EXPECT_EQ(body.counts.mul, 0);
}

TEST_F(StatementWriterTest, SharedSumAsFactorIsParenthesized) {
  const ExprId sum = g.share(g.add(p0, p1));
  const FunctionBody body = write_statements(g, {{"W[0]", g.mul(sum, c1), ""}}, Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{"const double c1 = std::cos(q[0]);", "W[0] = c1 * (p[0] + p[1]);"}));
  EXPECT_EQ(body.counts.mul, 1);
  EXPECT_EQ(body.counts.add, 1);
  EXPECT_EQ(body.counts.trig, 1);
}

TEST_F(StatementWriterTest, SharedIntermediateUsedTwiceIsComputedOnce) {
  const ExprId sum = g.share(g.add(p0, p1));
  const FunctionBody body = write_statements(
      g, {{"W[0]", g.mul(sum, s1), "XX1"}, {"W[1]", g.mul(sum, c1), "XY1"}}, Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "const double c1 = std::cos(q[0]);",
                            "const double t0 = p[0] + p[1];",
                            "W[0] = s1 * t0;  // XX1",
                            "W[1] = c1 * t0;  // XY1",
                        }));
  EXPECT_EQ(body.counts.mul, 2);
  EXPECT_EQ(body.counts.add, 1);
  EXPECT_EQ(body.counts.trig, 2);
}

TEST_F(StatementWriterTest, ASumReadNegatedMostlyIsStoredNegated) {
  // Three outputs read the shared sum through a coefficient of -1: storing -(p[0] + s1) costs
  // one leading negation and saves three.
  const ExprId sum = g.share(g.add(p0, s1));
  const FunctionBody body = write_statements(g,
                                             {{"W[0]", g.neg(g.mul(q0, sum)), ""},
                                              {"W[1]", g.neg(g.mul(p2, sum)), ""},
                                              {"W[2]", g.neg(g.mul(c1, sum)), ""}},
                                             Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "const double c1 = std::cos(q[0]);",
                            "const double t0 = -p[0] - s1;",
                            "W[0] = q[0] * t0;",
                            "W[1] = p[2] * t0;",
                            "W[2] = c1 * t0;",
                        }));
  EXPECT_EQ(body.counts.mul, 3);
  EXPECT_EQ(body.counts.add, 2);
}

TEST_F(StatementWriterTest, ASumWhoseSignIsTakenIsNotStoredNegated) {
  // sign(-t) would print its negation twice.
  const ExprId sum = g.share(g.add(p0, s1));
  const FunctionBody body = write_statements(g,
                                             {{"W[0]", g.neg(g.mul(q0, sum)), ""},
                                              {"W[1]", g.neg(g.mul(p2, sum)), ""},
                                              {"W[2]", g.neg(g.mul(c1, sum)), ""},
                                              {"W[3]", g.sign(sum), ""}},
                                             Scalar::kDouble);
  EXPECT_NE(std::find(body.lines.begin(), body.lines.end(), "const double t0 = p[0] + s1;"),
            body.lines.end());
  EXPECT_NE(std::find(body.lines.begin(), body.lines.end(), "W[0] = -q[0] * t0;"),
            body.lines.end());
}

TEST_F(StatementWriterTest, TemporariesAreNumberedInEmissionOrder) {
  const ExprId first_built = g.add(p0, p1);
  const ExprId second_built = g.add(p1, p2);
  const FunctionBody body = write_statements(g,
                                             {{"W[0]", g.mul(second_built, s1), ""},
                                              {"W[1]", g.mul(first_built, c1), ""},
                                              {"W[2]", g.mul(first_built, second_built), ""}},
                                             Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "const double c1 = std::cos(q[0]);",
                            "const double t0 = p[1] + p[2];",
                            "W[0] = s1 * t0;",
                            "const double t1 = p[0] + p[1];",
                            "W[1] = c1 * t1;",
                            "W[2] = t1 * t0;",
                        }));
  EXPECT_EQ(body.counts.mul, 3);
  EXPECT_EQ(body.counts.add, 2);
}

TEST_F(StatementWriterTest, LeavesAndConstantsAsOutputs) {
  const FunctionBody body = write_statements(
      g, {{"W[0]", s1, "XX1"}, {"W[1]", g.constant(-3.5), ""}, {"W[2]", g.one(), ""}},
      Scalar::kDouble);
  EXPECT_EQ(body.lines, (Lines{
                            "const double s1 = std::sin(q[0]);",
                            "W[0] = s1;  // XX1",
                            "W[1] = -3.5;",
                            "W[2] = 1.0;",
                        }));
  EXPECT_EQ(body.counts.mul, 0);
  EXPECT_EQ(body.counts.add, 0);
  EXPECT_EQ(body.counts.trig, 1);
}

TEST_F(StatementWriterTest, FloatUsesFloatDeclarationsAndLiterals) {
  const ExprId e = g.add(s1, p0);
  const FunctionBody body =
      write_statements(g,
                       {{"W[0]", g.mul(e, q0), "XX1"},
                        {"W[1]", g.mul(e, p1), ""},
                        {"W[2]", g.zero(), ""},
                        {"W[3]", g.add(g.mul(g.constant(0.225), c1), p2), ""}},
                       Scalar::kFloat);
  EXPECT_EQ(body.lines, (Lines{
                            "const float s1 = std::sin(q[0]);",
                            "const float c1 = std::cos(q[0]);",
                            "const float t0 = p[0] + s1;",
                            "W[0] = q[0] * t0;  // XX1",
                            "W[1] = p[1] * t0;",
                            "W[3] = p[2] + 0.225f * c1;",
                        }));
}

TEST_F(StatementWriterTest, SignLeavesUseTheScalarLiterals) {
  const ExprId sg = g.symbol(Symbol{"sg1", SymbolKind::kSign, "dq[0]"});
  const FunctionBody body = write_statements(g, {{"tau[0]", g.mul(sg, p0), ""}}, Scalar::kFloat);
  ASSERT_EQ(body.lines.size(), 2u);
  EXPECT_EQ(body.lines[1], "tau[0] = p[0] * sg1;");
  EXPECT_EQ(body.lines[0].rfind("const float sg1 = ", 0), 0u) << body.lines[0];
  EXPECT_EQ(body.lines[0], "const float sg1 = static_cast<float>((dq[0] > 0.0f) - (dq[0] < 0.0f));");
  EXPECT_EQ(body.lines[0].find("double"), std::string::npos) << body.lines[0];
  EXPECT_EQ(body.counts.trig, 0);
}

TEST_F(StatementWriterTest, ReciprocalsPrintAsOneDivisionCountedAsAMultiplication) {
  const FunctionBody body =
      write_statements(g,
                       {{"y[0]", g.inv(p0), ""},
                        {"y[1]", g.mul(p1, g.inv(p0)), ""},
                        {"y[2]", g.inv(g.mul(p1, p2)), ""},
                        {"y[3]", g.inv(g.add(p1, p2)), ""}},
                       Scalar::kDouble);
  // 1 / p[0] is used twice: a temporary.
  EXPECT_EQ(body.lines, (Lines{
                            "const double t0 = 1.0 / p[0];",
                            "y[0] = t0;",
                            "y[1] = p[1] * t0;",
                            "y[2] = 1.0 / (p[1] * p[2]);",
                            "y[3] = 1.0 / (p[1] + p[2]);",
                        }));
  EXPECT_EQ(body.counts.mul, 5);  // three divisions and two products
  EXPECT_EQ(body.counts.add, 1);
  const FunctionBody single =
      write_statements(g, {{"y[0]", g.mul({p1, p2, g.inv(p0)}), ""}}, Scalar::kFloat);
  EXPECT_EQ(single.lines, (Lines{"y[0] = p[1] * p[2] * (1.0f / p[0]);"}));
  EXPECT_EQ(single.counts.mul, 3);
}

// ---- Operation counts against the text, and the text's values against the DAG ----

// The operations a statement line performs: '*' is a multiplication; every '+' and '-' that
// is neither part of a number's exponent nor the sign of a literal is an addition,
// subtraction or negation.
OpCounts count_text(const Lines& lines) {
  OpCounts counts;
  for (const std::string& raw : lines) {
    if (raw.find("std::sin(") != std::string::npos || raw.find("std::cos(") != std::string::npos) {
      ++counts.trig;
      continue;
    }
    std::string line = raw.substr(0, raw.find("//"));
    line = line.substr(line.find(" = ") + 3);
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (line[i] == '*') ++counts.mul;
      if (line[i] == '+' || line[i] == '-') {
        const bool exponent =
            i >= 2 && line[i - 1] == 'e' &&
            (std::isdigit(static_cast<unsigned char>(line[i - 2])) || line[i - 2] == '.');
        // A unary '-' glued to a digit is a literal's sign, not an operation ("-2.0 * x").
        const bool literal_sign = line[i] == '-' && i + 1 < line.size() &&
                                  std::isdigit(static_cast<unsigned char>(line[i + 1]));
        if (!exponent && !literal_sign) ++counts.add;
      }
    }
  }
  return counts;
}

// A tiny interpreter for the statements: declarations "const T x = e;", sin/cos, outputs
// "target = e;". Grammar: sum := product (('+'|'-') product)*; product := unary ('*' unary)*;
// unary := '-' unary | number | name | name '[' int ']' | '(' sum ')' | std::sin/cos '(' sum ')'.
class Interpreter {
 public:
  explicit Interpreter(std::map<std::string, double> inputs) : vars_(std::move(inputs)) {}

  // Runs one line; throws std::runtime_error on text it does not understand.
  void run(const std::string& raw) {
    std::string line = raw.substr(0, raw.find("//"));
    while (!line.empty() && line.back() == ' ') line.pop_back();
    if (line.empty() || line.back() != ';') throw std::runtime_error("no ';': " + raw);
    line.pop_back();
    const std::size_t eq = line.find(" = ");
    if (eq == std::string::npos) throw std::runtime_error("no ' = ': " + raw);
    std::string target = line.substr(0, eq);
    const bool declaration = target.rfind("const ", 0) == 0;
    if (declaration) target = target.substr(target.rfind(' ') + 1);
    text_ = line.substr(eq + 3);
    pos_ = 0;
    const double value = sum();
    if (pos_ != text_.size()) throw std::runtime_error("trailing text in: " + raw);
    if (declaration && vars_.count(target)) throw std::runtime_error("redeclared: " + target);
    if (!declaration && outputs_.count(target)) throw std::runtime_error("rewritten: " + target);
    (declaration ? vars_ : outputs_)[target] = value;
  }

  const std::map<std::string, double>& outputs() const { return outputs_; }

 private:
  void skip_spaces() {
    while (pos_ < text_.size() && text_[pos_] == ' ') ++pos_;
  }
  bool accept(char c) {
    skip_spaces();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!accept(c)) throw std::runtime_error(std::string("expected '") + c + "' in " + text_);
  }

  double sum() {
    double value = product();
    while (true) {
      if (accept('+')) {
        value += product();
      } else if (accept('-')) {
        value -= product();
      } else {
        return value;
      }
    }
  }
  double product() {
    double value = unary();
    while (accept('*')) value *= unary();
    return value;
  }
  double unary() {
    if (accept('-')) return -unary();
    if (accept('(')) {
      const double value = sum();
      expect(')');
      return value;
    }
    skip_spaces();
    if (pos_ >= text_.size()) throw std::runtime_error("unexpected end: " + text_);
    if (std::isdigit(static_cast<unsigned char>(text_[pos_]))) {
      const char* start = text_.c_str() + pos_;
      char* end = nullptr;
      const double value = std::strtod(start, &end);
      pos_ += static_cast<std::size_t>(end - start);
      if (pos_ < text_.size() && text_[pos_] == 'f') ++pos_;
      return value;
    }
    std::string name;
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) ||
                                   text_[pos_] == '_' || text_[pos_] == ':')) {
      name += text_[pos_++];
    }
    if (name.empty()) throw std::runtime_error("unexpected text: " + text_.substr(pos_));
    if (name == "std::sin" || name == "std::cos") {
      expect('(');
      const double argument = sum();
      expect(')');
      return name == "std::sin" ? std::sin(argument) : std::cos(argument);
    }
    if (pos_ < text_.size() && text_[pos_] == '[') {
      while (pos_ < text_.size() && text_[pos_] != ']') name += text_[pos_++];
      if (pos_ == text_.size()) throw std::runtime_error("unclosed '[' in " + text_);
      name += text_[pos_++];
    }
    const auto found = vars_.find(name);
    if (found == vars_.end()) throw std::runtime_error("'" + name + "' used before it is defined");
    return found->second;
  }

  std::map<std::string, double> vars_;
  std::map<std::string, double> outputs_;
  std::string text_;
  std::size_t pos_ = 0;
};

// |value| bound of every node: the same formula on absolute values, for error tolerances.
std::vector<double> magnitudes(const ExprGraph& g, const std::vector<double>& values) {
  std::vector<double> m(g.size());
  for (ExprId i = 0; i < g.size(); ++i) {
    const Node& n = g.node(i);
    switch (n.op) {
      case Op::kConstant:
      case Op::kSymbol:
        m[i] = std::fabs(values[i]);
        break;
      case Op::kShare:
        m[i] = m[n.args[0]];
        break;
      case Op::kSign:
        m[i] = 1;
        break;
      case Op::kInv:  // not built by the random graphs here
        m[i] = std::fabs(values[i]);
        break;
      case Op::kAdd:
        m[i] = 0;
        for (ExprId a : n.args) m[i] += m[a];
        break;
      case Op::kMul:
        m[i] = 1;
        for (ExprId a : n.args) m[i] *= m[a];
        break;
    }
  }
  return m;
}

struct RandomBody {
  ExprGraph g;
  std::vector<FunctionOutput> outputs;
};

// A random function: a pool of leaves grown by add/sub/mul/neg/share and small constants;
// outputs are the last pool entries plus random earlier ones (so some are shared).
void build_random(RandomBody& r, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  auto pick = [&engine](std::size_t n) { return static_cast<std::size_t>(engine() % n); };
  ExprGraph& g = r.g;
  std::vector<ExprId> pool = {g.symbol(Symbol{"q[0]", SymbolKind::kInput, ""}),
                              g.symbol(Symbol{"s1", SymbolKind::kSin, "q[0]"}),
                              g.symbol(Symbol{"c1", SymbolKind::kCos, "q[0]"}),
                              g.symbol(Symbol{"q[1]", SymbolKind::kInput, ""}),
                              g.symbol(Symbol{"s2", SymbolKind::kSin, "q[1]"}),
                              g.symbol(Symbol{"c2", SymbolKind::kCos, "q[1]"}),
                              g.symbol(Symbol{"p[0]", SymbolKind::kInput, ""}),
                              g.symbol(Symbol{"p[1]", SymbolKind::kInput, ""}),
                              g.symbol(Symbol{"p[2]", SymbolKind::kInput, ""})};
  const std::size_t steps = 20 + pick(60);
  for (std::size_t i = 0; i < steps; ++i) {
    const ExprId a = pool[pick(pool.size())];
    const ExprId b = pool[pick(pool.size())];
    switch (pick(7)) {
      case 0:
        pool.push_back(g.add(a, b));
        break;
      case 1:
        pool.push_back(g.sub(a, b));
        break;
      case 2:
        pool.push_back(g.mul(a, b));
        break;
      case 3:
        pool.push_back(g.neg(a));
        break;
      case 4:
        pool.push_back(g.share(a));
        break;
      case 5:
        pool.push_back(g.mul(g.constant(0.25 * (static_cast<double>(pick(17)) - 8)), a));
        break;
      default:
        pool.push_back(g.add(g.constant(static_cast<double>(pick(5)) - 2), a));
        break;
    }
  }
  const std::size_t count = 1 + pick(8);
  for (std::size_t k = 0; k < count; ++k) {
    ExprId value = k % 2 ? pool[pick(pool.size())] : pool[pool.size() - 1 - k];
    // A bare negative constant output ("W[0] = -2.0;") is left out: its count is the subject
    // of NegativeConstantCountsTheSameAloneAndAsFirstTerm.
    if (g.is_constant(value) && g.constant_value(value) < 0) value = g.neg(value);
    r.outputs.push_back(
        {"W[" + std::to_string(k) + "]", value, k % 3 ? "" : "P" + std::to_string(k)});
  }
}

TEST(StatementWriterRandom, CountsMatchTheTextAndTheTextComputesTheDag) {
  // Over all seeds the bodies must exercise temporaries, parentheses and subtractions.
  int temporaries = 0, parentheses = 0, subtractions = 0;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    RandomBody r;
    build_random(r, seed);
    const FunctionBody body = write_statements(r.g, r.outputs, Scalar::kDouble);
    std::string text;
    for (const std::string& line : body.lines) {
      text += line + "\n";
      temporaries += line.rfind("const double t", 0) == 0;
      parentheses += line.find(" * (") != std::string::npos;
      subtractions += line.find(" - ") != std::string::npos;
    }
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);

    const OpCounts expected = count_text(body.lines);
    ASSERT_EQ(body.counts.mul, expected.mul);
    ASSERT_EQ(body.counts.add, expected.add);
    ASSERT_EQ(body.counts.trig, expected.trig);
    ASSERT_EQ(text.find("+ -"), std::string::npos);
    ASSERT_EQ(text.find("- -"), std::string::npos);
    ASSERT_EQ(text.find("--"), std::string::npos);

    std::mt19937_64 engine(seed + 7777);
    std::uniform_real_distribution<double> uniform(-2.0, 2.0);
    const std::map<std::string, double> inputs = {{"q[0]", uniform(engine)},
                                                  {"q[1]", uniform(engine)},
                                                  {"p[0]", uniform(engine)},
                                                  {"p[1]", uniform(engine)},
                                                  {"p[2]", uniform(engine)}};
    Interpreter interpreter(inputs);
    for (const std::string& line : body.lines) {
      try {
        interpreter.run(line);
      } catch (const std::runtime_error& error) {
        FAIL() << error.what();
      }
    }
    const std::vector<double> values = r.g.evaluate([&](const Symbol& s) {
      switch (s.kind) {
        case SymbolKind::kSin:
          return std::sin(inputs.at(s.input));
        case SymbolKind::kCos:
          return std::cos(inputs.at(s.input));
        default:
          return inputs.at(s.name);
      }
    });
    const std::vector<double> bound = magnitudes(r.g, values);
    // Outputs that are the constant 0 are not written: the caller zeroes the array once.
    std::size_t written = 0;
    for (const FunctionOutput& out : r.outputs) written += !r.g.is_zero(out.value);
    ASSERT_EQ(interpreter.outputs().size(), written);
    for (const FunctionOutput& out : r.outputs) {
      if (r.g.is_zero(out.value)) {
        ASSERT_EQ(interpreter.outputs().count(out.target), 0u) << out.target;
        continue;
      }
      ASSERT_NEAR(interpreter.outputs().at(out.target), values[out.value],
                  1e-12 * std::max(1.0, bound[out.value]))
          << out.target;
    }
  }
  EXPECT_GT(temporaries, 100);
  EXPECT_GT(parentheses, 50);
  EXPECT_GT(subtractions, 100);
}

TEST(StatementWriterRandom, TemporariesAreDeclaredInOrderAndEachIsUsedTwice) {
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    RandomBody r;
    build_random(r, seed);
    const FunctionBody body = write_statements(r.g, r.outputs, Scalar::kDouble);
    std::string text;
    for (const std::string& line : body.lines) text += line + "\n";
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    int next = 0;
    for (std::size_t i = 0; i < body.lines.size(); ++i) {
      const std::string& line = body.lines[i];
      if (line.rfind("const double t", 0) != 0) continue;
      const std::string name = "t" + std::to_string(next++);
      ASSERT_EQ(line.rfind("const double " + name + " = ", 0), 0u) << line;
      // Uses as a whole word in the following lines.
      int uses = 0;
      for (std::size_t j = i + 1; j < body.lines.size(); ++j) {
        const std::string& later = body.lines[j];
        for (std::size_t at = later.find(name); at != std::string::npos;
             at = later.find(name, at + 1)) {
          const std::size_t after = at + name.size();
          const bool word_start =
              at == 0 || !std::isalnum(static_cast<unsigned char>(later[at - 1]));
          const bool word_end =
              after == later.size() || !std::isalnum(static_cast<unsigned char>(later[after]));
          if (word_start && word_end) ++uses;
        }
      }
      EXPECT_GE(uses, 2) << name << " is computed but used " << uses << " time(s)";
    }
  }
}

TEST(StatementWriterRandom, FloatTextHasOnlyFloatLiterals) {
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    RandomBody r;
    build_random(r, seed);
    const FunctionBody body = write_statements(r.g, r.outputs, Scalar::kFloat);
    const FunctionBody twin = write_statements(r.g, r.outputs, Scalar::kDouble);
    EXPECT_EQ(body.counts.mul, twin.counts.mul);
    EXPECT_EQ(body.counts.add, twin.counts.add);
    EXPECT_EQ(body.counts.trig, twin.counts.trig);
    for (const std::string& raw : body.lines) {
      EXPECT_EQ(raw.find("double"), std::string::npos) << raw;
      const std::string line = raw.substr(0, raw.find("//"));
      // Every number ends in 'f': a digit followed by anything but a digit, '.', 'e', a sign
      // after 'e', 'f', or ']' (array index) is a double literal.
      for (std::size_t i = 0; i < line.size(); ++i) {
        if (!std::isdigit(static_cast<unsigned char>(line[i]))) continue;
        const bool in_name =
            i > 0 && (std::isalpha(static_cast<unsigned char>(line[i - 1])) || line[i - 1] == '[');
        if (in_name) {
          while (i + 1 < line.size() && std::isdigit(static_cast<unsigned char>(line[i + 1]))) ++i;
          continue;
        }
        std::size_t j = i;
        while (j < line.size() &&
               (std::isdigit(static_cast<unsigned char>(line[j])) || line[j] == '.' ||
                line[j] == 'e' || ((line[j] == '-' || line[j] == '+') && line[j - 1] == 'e'))) {
          ++j;
        }
        EXPECT_TRUE(j < line.size() && line[j] == 'f') << "double literal in: " << raw;
        i = j;
      }
    }
  }
}

TEST(StatementWriterRandom, SameInputSameText) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    RandomBody a, b;
    build_random(a, seed);
    build_random(b, seed);
    EXPECT_EQ(write_statements(a.g, a.outputs, Scalar::kDouble).lines,
              write_statements(b.g, b.outputs, Scalar::kDouble).lines);
  }
}

TEST(StatementWriterRandom, AReusedWorkspaceGivesTheFreshTextAndEndsClear) {
  // The emitter writes every body of a model with one workspace, which each call must leave
  // all zero: a body written after others is the text a fresh workspace gives.
  WriterWorkspace workspace;
  int bodies = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    RandomBody r;
    build_random(r, seed);
    for (std::size_t k = 0; k < r.outputs.size(); ++k) {
      const std::vector<FunctionOutput> outputs(r.outputs.begin() + k, r.outputs.end());
      for (Scalar scalar : {Scalar::kDouble, Scalar::kFloat}) {
        const FunctionBody reused =
            write_statements(r.g, outputs, scalar, TrigSource::kCompute, workspace);
        EXPECT_EQ(reused.lines, write_statements(r.g, outputs, scalar).lines) << seed;
        ASSERT_TRUE(workspace.all_zero()) << "seed " << seed << ", outputs from " << k;
        ++bodies;
      }
    }
  }
  EXPECT_GT(bodies, 300);
}

}  // namespace
}  // namespace modelgen::gen
